// Rolling and spinning resistance of a cylinder or ring on a fixed plane (issue 38 item 3,
// components/impedance/rolling_resistance.hpp), against closed forms on generated scenes:
// random mass, radius, length, solid or hollow, mu, c, s, speeds, and a random plane (its
// normal n anywhere, gravity -g n, so the law's frame is not the world's).
//
// Rolling on its rim. A cylinder of mass m, radius R, J = k m R^2 about its axis a (k = 1/2
// solid, 1 a ring) rolls without slipping along t = n x a, v = v0 t, angular velocity
// -(v0 / R) a. Its two rim contacts push it with a friction force F t at the points -R n
// and carry N = m g between them; `rolling_resistance` c resists the roll with a torque c N
// about a. As for a ball (test_rolling_resistance.cpp):
//   m v' = F,   J w' = -R F - c m g   with v = -R w,
// so v' = -c g / ((1 + k) R) = -a_r: a_r = 2/3 g c / R solid, g c / (2 R) a ring. It stops at
// v0 / a_r after v0^2 / (2 a_r), as long as m a_r < mu m g.
//
// Spinning on a face. A coin lying on its face (axis a = n) spun at w0 about n meets the
// spin element's torque s N = s m g and, from its three face contacts (the lower cap's rim
// tripod, cylinder_rim_map.hpp) sliding at the rim, mu N R: J_n w' = -(s + mu R) m g, J_n =
// k m R^2 the moment about the normal. With mu = 0 this is the spinning coin's closed form
// w' = -s N / J_n, a stop at J_n w0 / (s N) = k R^2 w0 / (s g); with mu > 0 the stop comes
// at k R^2 w0 / ((s + mu R) g).
//
// Once stopped, the elements hold the body: position and orientation do not creep for 10 s.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "core/simulation.hpp"
#include "core/types.hpp"
#include "rolling_cases.hpp"
#include "scene/scene.hpp"
#include "trajectory_rows.hpp"

using namespace stiction;
using core::Vec3;
using testing::column3;
using testing::column_at;
using testing::figure;
using testing::Random;
using testing::row_at;
using testing::stick_time;

namespace {

constexpr double kG = 9.8;
constexpr double kK = 1e6;

struct Cylinder {
  double mass = 1.0, radius = 0.1, length = 0.05;
  bool hollow = false;
  double mu = 0.5;
  double rolling = 1e-3, spin = 1e-3;  // c and s (m)
  Vec3 normal = Vec3::UnitZ();         // the plane's; gravity is -g normal
  // The body frame's axes in world coordinates: z_b is the cylinder's axis (`axis` = z).
  Vec3 x_b = Vec3::UnitX(), y_b = Vec3::UnitY(), z_b = Vec3::UnitZ();
  Vec3 position = Vec3::Zero(), velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();  // body frame
  double torque = 0.0;                   // N m about the axis, applied throughout (0: none)
  double k() const { return hollow ? 1.0 : 0.5; }
};

std::string vec(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string cylinder_scene(const Cylinder& c, const char* integrator, double dt, double duration) {
  Eigen::Matrix3d r;
  r << c.x_b, c.y_b, c.z_b;
  const core::Quat q(r);
  std::ostringstream s;
  s.precision(17);
  s << "name = \"generated_cylinder\"\ngravity = " << vec(-kG * c.normal) << "\n"
    << "[simulation]\nintegrator = \"" << integrator << "\"\ndt = " << dt
    << "\nduration = " << duration << "\noutput_rate = 1000.0\n"
    << "[bodies.can]\ntype = \"rigid_body\"\nmass = " << c.mass
    << "\nshape = \"cylinder\"\nradius = " << c.radius << "\nlength = " << c.length
    << "\nhollow = " << (c.hollow ? "true" : "false") << "\naxis = [0.0, 0.0, 1.0]\n"
    << "position = " << vec(c.position) << "\nvelocity = " << vec(c.velocity) << "\n"
    << "orientation = [" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\n"
    << "angular_velocity = " << vec(c.angular_velocity) << "\n"
    << "[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"can\"\nnormal = " << vec(c.normal)
    << "\nstiffness = " << kK << "\ndamping = " << std::sqrt(kK * c.mass) << "\nmu = " << c.mu
    << "\nrolling_resistance = " << c.rolling << "\nspin_friction = " << c.spin << "\n";
  if (c.torque != 0.0) {
    s << "[impedances.twist]\ntype = \"torque_source\"\nbody = \"can\"\naxis = [0.0, 0.0, 1.0]\n"
      << "torque = " << c.torque << "\n";
  }
  return s.str();
}

core::RunResult run(const std::string& text) {
  return testing::run_generated(text, "generated_cylinder.toml");
}

Cylinder random_cylinder(Random& r) {
  Cylinder c;
  c.mass = r.uniform(0.2, 3.0);
  c.radius = r.uniform(0.03, 0.3);
  c.hollow = r.uniform(0.0, 1.0) < 0.5;
  c.mu = r.uniform(0.3, 0.8);
  c.normal = r.unit();
  return c;
}

struct Integrator {
  const char* name;
  double dt;
};
constexpr Integrator kIntegrators[] = {{"rk4", 1e-4}, {"implicit", 1e-3}};

// Position and orientation of the body from `from` to `to`: the largest change of an entry.
double creep(const core::Trajectory& tr, double from, double to) {
  return testing::pose_change(tr, "can", from, to);
}

}  // namespace

TEST_CASE(
    "rolling resistance: a cylinder or ring rolling on its rim decelerates at "
    "c g / ((1 + k) R), stops at v0 / a_r and then stays put",
    "[rolling][cylinder]") {
  Random r{std::mt19937(3838)};
  for (const Integrator in : kIntegrators) {
    double worst_a = 0.0, worst_t = 0.0, worst_x = 0.0, worst_creep = 0.0;
    for (int k = 0; k < 4; ++k) {
      Cylinder c = random_cylinder(r);
      c.length = r.uniform(0.3, 3.0) * c.radius;
      // On its rim: the axis in the plane, rolling along t = n x a.
      const Vec3 n = c.normal;
      c.z_b = r.unit_normal_to(n);
      const double turn = r.uniform(0.0, 6.283185307179586);  // about the axis: any rim point
      c.x_b = std::cos(turn) * n + std::sin(turn) * c.z_b.cross(n);
      c.y_b = c.z_b.cross(c.x_b);
      const Vec3 t = n.cross(c.z_b);
      const double a_r = r.uniform(0.05, c.mu * kG / 4.0);
      c.rolling = a_r * (1.0 + c.k()) * c.radius / kG;
      c.spin = r.uniform(0.1, 1.0) * c.rolling;
      const double t_stop = r.uniform(0.5, 2.0);
      const double v0 = a_r * t_stop;
      // Two rim points carry m g: each sinks by m g / (2 K).
      c.position = (c.radius - c.mass * kG / (2.0 * kK)) * n;
      c.velocity = v0 * t;
      c.angular_velocity = Vec3(0.0, 0.0, -v0 / c.radius);  // -(v0 / R) a, body frame
      const double hold = 10.0, duration = t_stop + 1.0 + hold;
      const core::RunResult result = run(cylinder_scene(c, in.name, in.dt, duration));
      INFO(in.name << " case " << k << ": m " << c.mass << ", R " << c.radius << ", L " << c.length
                   << (c.hollow ? " ring" : " solid") << ", mu " << c.mu << ", c " << c.rolling
                   << ", n " << n.transpose() << ", v0 " << v0 << ", a_r " << a_r
                   << ", stop due at " << t_stop);
      REQUIRE_FALSE(result.instability);
      const auto& tr = result.trajectory;
      // The deceleration along t between a fifth and four fifths of the way.
      const double t1 = tr.at(row_at(tr, 0.2 * t_stop), 0), t2 = tr.at(row_at(tr, 0.8 * t_stop), 0);
      const double measured =
          (column3(tr, "can.v", t1) - column3(tr, "can.v", t2)).dot(t) / (t2 - t1);
      CHECK(measured == Approx(a_r).epsilon(1e-8));
      worst_a = std::max(worst_a, std::abs(measured / a_r - 1.0));
      // The element's torque on the body: c N about the axis, against the roll (w = -v0/R a).
      const Vec3 tau = column3(tr, "ground.rolling.tau", 0.5 * t_stop);
      CHECK(tau.dot(c.z_b) == Approx(c.rolling * c.mass * kG).epsilon(1e-4));
      CHECK((tau - tau.dot(c.z_b) * c.z_b).norm() < 1e-9 * c.rolling * c.mass * kG);
      // It stops (the rolling element sticks) on time, having rolled v0^2 / (2 a_r).
      const double stop = stick_time(result, "ground.rolling");
      CHECK(stop == Approx(t_stop).margin(1e-8));
      worst_t = std::max(worst_t, std::abs(stop - t_stop));
      const double travelled = (column3(tr, "can.p", t_stop + 1.0) - c.position).dot(t);
      // (Implicit Euler's first-order error on the distance is about v0 dt / 2.)
      CHECK(travelled == Approx(v0 * v0 / (2.0 * a_r)).epsilon(1e-4).margin(v0 * in.dt));
      worst_x = std::max(worst_x, std::abs(travelled / (v0 * v0 / (2.0 * a_r)) - 1.0));
      // And stays put: no creep of the position or the orientation over 10 s.
      const double moved = creep(tr, t_stop + 1.0, duration);
      CHECK(moved < 1e-12);
      worst_creep = std::max(worst_creep, moved);
    }
    figure("rim roll", in.name, "deceleration vs c g / ((1 + k) R), relative", worst_a);
    figure("rim roll", in.name, "stop (stick event) vs v0 / a_r, s", worst_t);
    figure("rim roll", in.name, "distance vs v0^2 / (2 a_r), relative", worst_x);
    figure("rim roll", in.name, "creep of p and q over 10 s after the stop", worst_creep);
  }
}

TEST_CASE(
    "spinning resistance: a coin spun on its face stops at J_n w0 / ((s + mu R) N), at "
    "J_n w0 / (s N) without friction, and does not creep afterwards",
    "[rolling][cylinder]") {
  Random r{std::mt19937(3839)};
  for (const Integrator in : kIntegrators) {
    double worst_a = 0.0, worst_t = 0.0, worst_creep = 0.0;
    double worst_a_mu = 0.0, worst_t_mu = 0.0;
    for (int k = 0; k < 6; ++k) {
      Cylinder c = random_cylinder(r);
      c.length = r.uniform(0.02, 0.3) * c.radius;  // a coin
      // Half the cases frictionless (the closed form s N / J_n alone), half with the face's
      // own sliding friction mu N R added.
      const bool frictionless = k % 2 == 0;
      if (frictionless) c.mu = 0.0;
      const Vec3 n = c.normal;
      c.z_b = n;  // flat on its face
      c.x_b = r.unit_normal_to(n);
      c.y_b = c.z_b.cross(c.x_b);
      c.spin = r.uniform(0.2, 1.0) * c.radius;
      c.rolling = r.uniform(0.01, 0.1) * c.radius;
      const double lever = c.spin + c.mu * c.radius;  // the torque over N
      const double alpha = lever * kG / (c.k() * c.radius * c.radius);
      const double t_spin = r.uniform(0.5, 2.0);
      const double w0 = alpha * t_spin;
      // The lower cap's three rim points carry m g: each sinks by m g / (3 K).
      c.position = (0.5 * c.length - c.mass * kG / (3.0 * kK)) * n;
      c.angular_velocity = Vec3(0.0, 0.0, w0);  // about the axis, here the normal
      const double hold = 10.0, duration = t_spin + 1.0 + hold;
      const core::RunResult result = run(cylinder_scene(c, in.name, in.dt, duration));
      INFO(in.name << " case " << k << ": m " << c.mass << ", R " << c.radius << ", L " << c.length
                   << (c.hollow ? " ring" : " solid") << ", mu " << c.mu << ", s " << c.spin
                   << ", n " << n.transpose() << ", w0 " << w0 << ", stop due at " << t_spin);
      REQUIRE_FALSE(result.instability);
      const auto& tr = result.trajectory;
      // The body's z is its axis, here the normal: w.z is the spin about the normal.
      const double t1 = tr.at(row_at(tr, 0.2 * t_spin), 0), t2 = tr.at(row_at(tr, 0.8 * t_spin), 0);
      const double measured =
          (column_at(tr, "can.w.z", t1) - column_at(tr, "can.w.z", t2)) / (t2 - t1);
      const double stop = stick_time(result, "ground.spin");
      // The spin element's torque: s N about the normal, against the spin.
      const Vec3 tau = column3(tr, "ground.spin.tau", 0.5 * t_spin);
      CHECK(tau.dot(n) == Approx(-c.spin * c.mass * kG).epsilon(1e-4));
      if (frictionless) {
        CHECK(measured == Approx(alpha).epsilon(1e-8));
        CHECK(stop == Approx(t_spin).margin(1e-8));
        worst_a = std::max(worst_a, std::abs(measured / alpha - 1.0));
        worst_t = std::max(worst_t, std::abs(stop - t_spin));
      } else {
        // The tripod's three points slide at the rim, each carrying mu N / 3 (measured to
        // 3e-10: their friction springs' lag behind the turning slip does not show).
        CHECK(measured == Approx(alpha).epsilon(1e-8));
        CHECK(stop == Approx(t_spin).epsilon(1e-8));
        worst_a_mu = std::max(worst_a_mu, std::abs(measured / alpha - 1.0));
        worst_t_mu = std::max(worst_t_mu, std::abs(stop / t_spin - 1.0));
      }
      // Spinning does not roll or move the coin, and once stopped it stays put.
      CHECK((column3(tr, "can.p", duration) - c.position).norm() < 1e-9);
      const double moved = creep(tr, t_spin + 1.0, duration);
      CHECK(moved < 1e-12);
      worst_creep = std::max(worst_creep, moved);
    }
    figure("coin spin", in.name, "mu = 0: angular decel. vs s N / J_n, relative", worst_a);
    figure("coin spin", in.name, "mu = 0: stop vs J_n w0 / (s N), s", worst_t);
    figure("coin spin", in.name, "mu > 0: angular decel. vs (s + mu R) N / J_n, rel.", worst_a_mu);
    figure("coin spin", in.name, "mu > 0: stop vs J_n w0 / ((s + mu R) N), relative", worst_t_mu);
    figure("coin spin", in.name, "creep of p and q over 10 s after the stop", worst_creep);
  }
}

TEST_CASE(
    "cylinder hold: a cylinder on its rim and a coin on its face do not creep under a torque "
    "below c N or s N",
    "[rolling][cylinder]") {
  // What holds them is the elements' stuck branch, e_dot equal to the coordinate exactly: the
  // torque about the axis loads the rolling element of a cylinder on its rim (the rim
  // contacts carry no torque about the axis) and the spin element of a coin on a
  // frictionless face (mu = 0: nothing else resists the turn). A law whose anchor leaked
  // (e_dot = w - r e, as a smooth model's does) would let them turn.
  Random r{std::mt19937(3842)};
  for (const Integrator in : kIntegrators) {
    double worst = 0.0;
    for (int k = 0; k < 4; ++k) {
      Cylinder c = random_cylinder(r);
      const bool rim = k % 2 == 0;
      const Vec3 n = c.normal;
      if (rim) {
        c.length = r.uniform(0.3, 3.0) * c.radius;
        c.z_b = r.unit_normal_to(n);
        c.x_b = n;
        c.position = (c.radius - c.mass * kG / (2.0 * kK)) * n;
        c.rolling = r.uniform(0.01, 0.1) * c.radius;
        c.spin = c.rolling;
        c.torque = r.uniform(0.3, 0.9) * c.rolling * c.mass * kG;
      } else {
        c.length = r.uniform(0.02, 0.3) * c.radius;
        c.mu = 0.0;
        c.z_b = n;
        c.x_b = r.unit_normal_to(n);
        c.position = (0.5 * c.length - c.mass * kG / (3.0 * kK)) * n;
        c.spin = r.uniform(0.2, 1.0) * c.radius;
        c.rolling = 0.1 * c.spin;
        c.torque = r.uniform(0.3, 0.9) * c.spin * c.mass * kG;
      }
      c.y_b = c.z_b.cross(c.x_b);
      const double duration = 11.0;
      const core::RunResult result = run(cylinder_scene(c, in.name, in.dt, duration));
      INFO(in.name << " case " << k << (rim ? " on its rim" : " on its face") << ": m " << c.mass
                   << ", R " << c.radius << ", L " << c.length << ", c " << c.rolling << ", s "
                   << c.spin << ", torque " << c.torque << ", n " << n.transpose());
      REQUIRE_FALSE(result.instability);
      // The element carries the torque...
      const Vec3 tau = column3(result.trajectory, rim ? "ground.rolling.tau" : "ground.spin.tau",
                               0.5 * duration);
      CHECK(tau.dot(c.z_b) == Approx(-c.torque).epsilon(1e-6));
      // ... and the body does not move once the load has settled.
      const double moved = creep(result.trajectory, 1.0, duration);
      CHECK(moved < 1e-12);
      worst = std::max(worst, moved);
    }
    figure("hold", in.name, "creep of p and q from 1 s to 11 s under the torque", worst);
  }
}

TEST_CASE(
    "rolling resistance on a cylinder: its rim points only, between bodies a sphere in the "
    "pair, refusals name the key",
    "[rolling][cylinder]") {
  auto refused = [](const std::string& text, const std::string& where, const std::string& key) {
    try {
      scene::load_scene(scene::SceneSource::from_text(text, "c.toml"));
      FAIL("accepted");
    } catch (const scene::InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find(where) != std::string::npos);
      CHECK(what.find(key) != std::string::npos);
    }
  };
  const std::string can = R"([bodies.can]
type = "rigid_body"
mass = 1.0
shape = "cylinder"
radius = 0.1
length = 0.2
)";
  // Listed points instead of the rim: no load the element could take as the cylinder's.
  refused(can + R"([impedances.ground]
type = "kikuuwe_contact"
body = "can"
points = [[0.0, 0.0, -0.1]]
spin_friction = 0.001
)",
          "c.toml:11:", "spin_friction");
  // Between two boxes: a box does not roll on a box.
  refused(R"([bodies.a]
type = "rigid_body"
mass = 1.0
shape = "box"
size = [0.1, 0.1, 0.1]
[bodies.b]
type = "rigid_body"
mass = 1.0
shape = "box"
size = [0.1, 0.1, 0.1]
position = [0.0, 0.0, 0.1]
[impedances.touch]
type = "kikuuwe_contact"
body = "b"
other = "a"
rolling_resistance = 0.001
)",
          "c.toml:16:", "rolling_resistance");
}
