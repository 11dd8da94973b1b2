// check's effective mass of each element (services::largest_mobility, read at the velocity
// its map names as conjugate to its force: CoordinateMap::conjugate_velocity_offset) against
// closed forms, on generated scenes of the wirings whose input is not [position, velocity]
// (issue 38 item 5: `check` said "no effective mass could be computed" for them):
// - a sphere's rolling and spinning resistance (a free torque, x_hat = [p, v, w]): the
//   sphere's inertia J = k m R^2 about any axis;
// - the same between two spheres (a couple on the relative angular velocity): 1 / (1/J_a +
//   1/J_b);
// - a pair contact (x_hat = [d, n, v_rel]) between two spheres: the contact point sees
//   1/m_a + 1/m_b along n, more across it (each sphere turns: L^2 / J more, L its lever);
// - a box corner with body-fixed anisotropic friction axes (x_hat = [p_c, v_c, axis]): the
//   corner's largest 1/m + (r x e)^T I^-1 (r x e) over the world axes e.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "core/network.hpp"
#include "scene/scene.hpp"
#include "services/dynamics_fingerprint.hpp"

using namespace stiction;

namespace {

std::mt19937 rng(3805);

double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); }

Eigen::Vector3d random_unit() {
  Eigen::Vector3d v;
  do {
    v = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
  } while (v.norm() < 0.2 || v.norm() > 1.0);
  return v.normalized();
}

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream o;
  o.precision(17);
  o << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return o.str();
}

// The element's mobility at the scene's initial state; fails the test if it is not there.
double mobility(const std::string& text, const std::string& element) {
  auto scene = scene::load_scene(scene::SceneSource::from_text(text, "generated_mass.toml"));
  core::Network& network = *scene.network;
  const core::Vec x0 = network.initial_state();
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    if (network.impedances()[i]->name() == element)
      return services::largest_mobility(network, static_cast<int>(i), x0);
  }
  FAIL("no element " << element);
  return 0.0;
}

struct Ball {
  double mass, radius;
  bool hollow;
  double inertia() const { return (hollow ? 2.0 / 3.0 : 0.4) * mass * radius * radius; }
};

Ball random_ball() { return {uniform(0.05, 8.0), uniform(0.01, 0.4), uniform(0, 1) < 0.5}; }

std::string ball_body(const std::string& name, const Ball& b, const Eigen::Vector3d& p) {
  std::ostringstream o;
  o.precision(17);
  o << "[bodies." << name << "]\ntype = \"rigid_body\"\nmass = " << b.mass << "\nshape = \""
    << (b.hollow ? "hollow_sphere" : "sphere") << "\"\nradius = " << b.radius
    << "\nposition = " << vec(p) << "\n";
  return o.str();
}

}  // namespace

TEST_CASE(
    "effective mass: rolling and spinning resistance see the sphere's inertia, on a plane "
    "and between two spheres",
    "[effective_mass]") {
  for (int k = 0; k < 12; ++k) {
    const Ball a = random_ball(), b = random_ball();
    const Eigen::Vector3d n = random_unit();
    std::ostringstream plane;
    plane.precision(17);
    plane << "name = \"generated_mass\"\ngravity = [0.0, 0.0, 0.0]\n"
          << ball_body("a", a, (a.radius - 1e-4) * n)
          << "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"a\"\nnormal = " << vec(n)
          << "\noffset = 0.0\nstiffness = 1e5\nmu = 0.5\nrolling_resistance = 0.001\n"
          << "spin_friction = 0.002\n";
    INFO("case " << k << ": m " << a.mass << ", R " << a.radius << (a.hollow ? " hollow" : "")
                 << ", n " << n.transpose());
    CHECK(mobility(plane.str(), "floor.rolling") == Approx(1.0 / a.inertia()).epsilon(1e-12));
    CHECK(mobility(plane.str(), "floor.spin") == Approx(1.0 / a.inertia()).epsilon(1e-12));

    std::ostringstream pair;
    pair.precision(17);
    pair << "name = \"generated_mass\"\ngravity = [0.0, 0.0, 0.0]\n"
         << ball_body("a", a, Eigen::Vector3d::Zero())
         << ball_body("b", b, -(a.radius + b.radius - 1e-4) * n)
         << "[impedances.touch]\ntype = \"kikuuwe_contact\"\nbody = \"a\"\nother = \"b\"\n"
         << "stiffness = 1e5\nmu = 0.5\nrolling_resistance = 0.001\nspin_friction = 0.002\n";
    INFO("pair with m " << b.mass << ", R " << b.radius << (b.hollow ? " hollow" : ""));
    const double couple = 1.0 / a.inertia() + 1.0 / b.inertia();
    CHECK(mobility(pair.str(), "touch.rolling") == Approx(couple).epsilon(1e-12));
    CHECK(mobility(pair.str(), "touch.spin") == Approx(couple).epsilon(1e-12));
    // The contact itself: along n the masses alone; across n each sphere also turns about
    // its centre, the contact point (midway between the surfaces, pair_contact_map.hpp) at
    // the lever L = R - d/2: 1/m + L^2/J each. The largest over the world axes lies between.
    const double depth = 1e-4, la = a.radius - 0.5 * depth, lb = b.radius - 0.5 * depth;
    const double along = 1.0 / a.mass + 1.0 / b.mass;
    const double across = along + la * la / a.inertia() + lb * lb / b.inertia();
    const double contact = mobility(pair.str(), "touch");
    CHECK(contact >= along * (1.0 - 1e-9));
    CHECK(contact <= across * (1.0 + 1e-9));
    // The world axis that sees the most: its share across n weighs the rotational part.
    double largest = 0.0;
    for (int e = 0; e < 3; ++e) {
      const double c = n[e] * n[e];
      largest = std::max(largest, c * along + (1.0 - c) * across);
    }
    CHECK(contact == Approx(largest).epsilon(1e-6));
  }
}

TEST_CASE(
    "effective mass: a box corner with body-fixed friction axes sees 1/m + (r x e) I^-1 (r x e)",
    "[effective_mass]") {
  for (int k = 0; k < 12; ++k) {
    const double m = uniform(0.2, 10.0);
    const Eigen::Vector3d size(uniform(0.05, 1.0), uniform(0.05, 1.0), uniform(0.05, 1.0));
    const double yaw = uniform(-M_PI, M_PI);
    const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    std::ostringstream s;
    s.precision(17);
    s << "name = \"generated_mass\"\ngravity = [0.0, 0.0, -9.8]\n"
      << "[bodies.box]\ntype = \"rigid_body\"\nmass = " << m
      << "\nshape = \"box\"\nsize = " << vec(size) << "\nposition = [0.0, 0.0, "
      << 0.5 * size.z() - 1e-5 << "]\n"
      << "orientation = [" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\n"
      << "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\nstiffness = 1e6\n"
      << "mu = [" << uniform(0.05, 0.3) << ", " << uniform(0.3, 0.9) << "]\n"
      << "friction_axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\nfriction_axes_frame = \"body\"\n";
    const Eigen::Vector3d I_body(m / 12.0 * (size.y() * size.y() + size.z() * size.z()),
                                 m / 12.0 * (size.x() * size.x() + size.z() * size.z()),
                                 m / 12.0 * (size.x() * size.x() + size.y() * size.y()));
    const Eigen::Matrix3d R = q.toRotationMatrix();
    const Eigen::Matrix3d I_inv = R * I_body.cwiseInverse().asDiagonal() * R.transpose();
    INFO("case " << k << ": m " << m << ", size " << size.transpose() << ", yaw " << yaw);
    // Corner i at (+-lx/2, +-ly/2, +-lz/2), the signs from bits 0, 1, 2 of i
    // (docs/scene_format.md).
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d local(((corner & 1) ? 0.5 : -0.5) * size.x(),
                                  ((corner & 2) ? 0.5 : -0.5) * size.y(),
                                  ((corner & 4) ? 0.5 : -0.5) * size.z());
      const Eigen::Vector3d r = R * local;
      double expected = 0.0;
      for (int e = 0; e < 3; ++e) {
        const Eigen::Vector3d arm = r.cross(Eigen::Vector3d::Unit(e));
        expected = std::max(expected, 1.0 / m + arm.dot(I_inv * arm));
      }
      INFO("floor." << corner);
      CHECK(mobility(s.str(), "floor." + std::to_string(corner)) == Approx(expected).epsilon(1e-9));
    }
  }
}
