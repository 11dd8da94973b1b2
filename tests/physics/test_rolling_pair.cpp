// Rolling and spinning resistance between two spheres in contact (issue 38 item 3,
// components/impedance/pair_rolling_resistance.hpp), against closed forms on generated
// scenes: no gravity, the spheres pressed together with a force F (a soft spring between
// their centres, stretched to carry F) along a random line of centres n, so N = F; random
// radii, masses, solid or hollow.
//
// Spinning. Sphere a (J_a) and sphere b (J_b) turn about n at w_a = w0 J_b / (J_a + J_b) and
// w_b = -w0 J_a / (J_a + J_b): relative spin w0, no angular momentum. The contact point is on
// the line of centres, so it does not slip; only the spin element acts, s N on a and -s N on
// b: the relative spin falls at s F (1 / J_a + 1 / J_b) and stops at
// w0 / (s F (1 / J_a + 1 / J_b)), both spheres then at rest.
//
// Rolling. The same pair counter-rotating about an axis u normal to n like two gears:
// w_a = W rho_b / (rho_a + rho_b) u, w_b = -W rho_a / (rho_a + rho_b) u, rho_i = r_i - d/2
// the levers of the contact point (midway between the surfaces, d = F / K the overlap), so
// the contact point does not slip and the relative roll is W. The rolling element puts G on a
// and -G on b (about u); the contact's friction T along t = u x n keeps the points together:
//   m_a v_a' = T, m_b v_b' = -T, J_a w_a' = -rho_a T + G, J_b w_b' = -rho_b T - G,
// and the no-slip condition v_a - rho_a w_a - v_b - rho_b w_b = 0 (along t) gives
//   T (1/m_a + 1/m_b + rho_a^2/J_a + rho_b^2/J_b) = G (rho_a/J_a - rho_b/J_b).
// With m_b chosen so that J_a / rho_a = J_b / rho_b, T = 0: the centres stay put, the pair
// has no angular momentum, and the relative roll falls at c F (1 / J_a + 1 / J_b), stopping
// at W / (c F (1 / J_a + 1 / J_b)) with both spheres at rest.
//
// Once stopped, the elements hold the pair: the relative position and orientation (seen
// from a, so that the pair's free drift as a whole, which nothing holds in empty space and
// whose angular momentum is zero only to rounding, does not count) do not creep.
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

constexpr double kK = 1e6;
// The spring that presses the pair together (N m^-1): a central force, along the line of
// centres whatever its direction. (Two opposite forces of fixed direction would buckle the
// pair: tilted by an angle, they form a couple that tilts it further.)
constexpr double kPull = 1e3;

struct Sphere {
  double mass = 1.0, radius = 0.1, k = 0.4;  // J = k m r^2
  Vec3 position = Vec3::Zero(), angular_velocity = Vec3::Zero();
  double inertia() const { return k * mass * radius * radius; }
};

struct Pair {
  Sphere a, b;
  Vec3 normal = Vec3::UnitZ();  // from b to a
  double force = 5.0;           // F, pressing them together
  double mu = 0.5, rolling = 1e-3, spin = 1e-3;
  double torque = 0.0;        // N m on a (and -torque on b) about `axis`, 0: none
  Vec3 axis = Vec3::UnitZ();  // a's body frame
};

std::string vec(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string body(const char* name, const Sphere& s) {
  std::ostringstream o;
  o.precision(17);
  o << "[bodies." << name << "]\ntype = \"rigid_body\"\nmass = " << s.mass << "\nshape = \""
    << (s.k < 0.5 ? "sphere" : "hollow_sphere") << "\"\nradius = " << s.radius
    << "\nposition = " << vec(s.position) << "\nangular_velocity = " << vec(s.angular_velocity)
    << "\n";
  return o.str();
}

std::string pair_scene(const Pair& p, const char* integrator, double dt, double duration) {
  std::ostringstream s;
  s.precision(17);
  s << "name = \"generated_pair\"\ngravity = [0.0, 0.0, 0.0]\n"
    << "[simulation]\nintegrator = \"" << integrator << "\"\ndt = " << dt
    << "\nduration = " << duration << "\noutput_rate = 1000.0\n"
    << body("a", p.a) << body("b", p.b)
    << "[impedances.pull]\ntype = \"spring_damper\"\nbody = \"a\"\nother = \"b\"\nstiffness = "
    << kPull << "\nlength = " << (p.b.position - p.a.position).norm() - p.force / kPull << "\n"
    << "[impedances.touch]\ntype = \"kikuuwe_contact\"\nbody = \"a\"\nother = \"b\"\nstiffness = "
    << kK << "\ndamping = " << std::sqrt(kK * std::min(p.a.mass, p.b.mass)) << "\nmu = " << p.mu
    << "\nrolling_resistance = " << p.rolling << "\nspin_friction = " << p.spin << "\n";
  if (p.torque != 0.0) {
    s << "[impedances.twist]\ntype = \"torque_source\"\nbody = \"a\"\nparent = \"b\"\naxis = "
      << vec(p.axis) << "\ntorque = " << p.torque << "\n";
  }
  return s.str();
}

core::RunResult run(const std::string& text) {
  return testing::run_generated(text, "generated_pair.toml");
}

// Two spheres touching along a random n, pressed by F; b's mass is left to the caller.
Pair random_pair(Random& r) {
  Pair p;
  p.a.mass = r.uniform(0.2, 3.0);
  p.a.radius = r.uniform(0.03, 0.3);
  p.a.k = r.uniform(0.0, 1.0) < 0.5 ? 0.4 : 2.0 / 3.0;
  p.b.mass = r.uniform(0.2, 3.0);
  p.b.radius = r.uniform(0.5, 2.0) * p.a.radius;
  p.b.k = r.uniform(0.0, 1.0) < 0.5 ? 0.4 : 2.0 / 3.0;
  p.mu = r.uniform(0.3, 0.8);
  p.force = r.uniform(1.0, 20.0);
  p.normal = r.unit();
  return p;
}

// Places b against a along -n with the overlap F / K that carries F (the spring pulls with F
// at that distance).
void place(Pair& p) {
  p.a.position = Vec3::Zero();
  p.b.position = -(p.a.radius + p.b.radius - p.force / kK) * p.normal;
}

struct Integrator {
  const char* name;
  double dt;
};
constexpr Integrator kIntegrators[] = {{"rk4", 1e-4}, {"implicit", 1e-3}};

core::Quat quat(const core::Trajectory& tr, const std::string& body, double t) {
  return core::Quat(column_at(tr, body + ".q.w", t), column_at(tr, body + ".q.x", t),
                    column_at(tr, body + ".q.y", t), column_at(tr, body + ".q.z", t));
}

// b's position and orientation in a's frame, from `from` to `to`: the largest change of an
// entry (m for the position, the quaternion's entries for the orientation).
double creep(const core::Trajectory& tr, double from, double to) {
  auto relative = [&](double t) {
    const core::Quat qa = quat(tr, "a", t);
    const Vec3 p = qa.conjugate() * (column3(tr, "b.p", t) - column3(tr, "a.p", t));
    const core::Quat q = qa.conjugate() * quat(tr, "b", t);
    Eigen::Matrix<double, 7, 1> out;
    out << p, q.w(), q.x(), q.y(), q.z();
    return out;
  };
  return (relative(to) - relative(from)).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE(
    "spinning resistance between two spheres: the relative spin stops at "
    "w0 / (s F (1 / J_a + 1 / J_b)), then no creep",
    "[rolling][pair]") {
  Random r{std::mt19937(3840)};
  for (const Integrator in : kIntegrators) {
    double worst_a = 0.0, worst_t = 0.0, worst_creep = 0.0;
    for (int k = 0; k < 3; ++k) {
      Pair p = random_pair(r);
      place(p);
      const double ja = p.a.inertia(), jb = p.b.inertia();
      const double t_spin = r.uniform(0.5, 2.0);
      const double w0 = r.uniform(2.0, 20.0);
      const double alpha = w0 / t_spin;
      p.spin = alpha / (p.force * (1.0 / ja + 1.0 / jb));
      p.rolling = r.uniform(0.1, 1.0) * p.spin;
      // The bodies start unrotated: body-frame and world angular velocities agree.
      p.a.angular_velocity = w0 * jb / (ja + jb) * p.normal;
      p.b.angular_velocity = -w0 * ja / (ja + jb) * p.normal;
      const double hold = 10.0, duration = t_spin + 1.0 + hold;
      const core::RunResult result = run(pair_scene(p, in.name, in.dt, duration));
      INFO(in.name << " case " << k << ": m " << p.a.mass << ", " << p.b.mass << ", r "
                   << p.a.radius << ", " << p.b.radius << ", F " << p.force << ", s " << p.spin
                   << ", w0 " << w0 << ", n " << p.normal.transpose() << ", stop due at "
                   << t_spin);
      REQUIRE_FALSE(result.instability);
      const auto& tr = result.trajectory;
      // Spinning about their fixed axis n, the bodies' w stays along n in both frames.
      auto relative = [&](double t) {
        return (column3(tr, "a.w", t) - column3(tr, "b.w", t)).dot(p.normal);
      };
      const double t1 = tr.at(row_at(tr, 0.2 * t_spin), 0), t2 = tr.at(row_at(tr, 0.8 * t_spin), 0);
      const double measured = (relative(t1) - relative(t2)) / (t2 - t1);
      CHECK(measured == Approx(alpha).epsilon(1e-8));
      worst_a = std::max(worst_a, std::abs(measured / alpha - 1.0));
      CHECK(column3(tr, "touch.spin.tau", 0.5 * t_spin).dot(p.normal) ==
            Approx(-p.spin * p.force).epsilon(1e-4));
      const double stop = stick_time(result, "touch.spin");
      CHECK(stop == Approx(t_spin).margin(1e-8));
      worst_t = std::max(worst_t, std::abs(stop - t_spin));
      const double moved = creep(tr, t_spin + 1.0, duration);
      CHECK(moved < 1e-11);  // rounding only, as in the rolling case below
      worst_creep = std::max(worst_creep, moved);
    }
    figure("pair spin", in.name, "relative decel. vs s F (1/J_a + 1/J_b), relative", worst_a);
    figure("pair spin", in.name, "stop (stick event) vs the closed form, s", worst_t);
    figure("pair spin", in.name, "creep of b's pose in a's frame, 10 s after the stop",
           worst_creep);
  }
}

TEST_CASE(
    "rolling resistance between two spheres: counter-rotating like gears, the relative roll "
    "stops at W / (c F (1 / J_a + 1 / J_b)), then no creep",
    "[rolling][pair]") {
  Random r{std::mt19937(3841)};
  for (const Integrator in : kIntegrators) {
    double worst_a = 0.0, worst_t = 0.0, worst_creep = 0.0, worst_still = 0.0;
    for (int k = 0; k < 3; ++k) {
      Pair p = random_pair(r);
      place(p);
      const double d = p.force / kK;
      const double rho_a = p.a.radius - 0.5 * d, rho_b = p.b.radius - 0.5 * d;
      // J_b / rho_b = J_a / rho_a: no friction force, no angular momentum.
      p.b.mass = p.a.inertia() * rho_b / (rho_a * p.b.k * p.b.radius * p.b.radius);
      const double ja = p.a.inertia(), jb = p.b.inertia();
      const Vec3 u = (r.unit().cross(p.normal)).normalized();
      const double t_stop = r.uniform(0.5, 2.0);
      const double w0 = r.uniform(2.0, 20.0);
      const double alpha = w0 / t_stop;
      p.rolling = alpha / (p.force * (1.0 / ja + 1.0 / jb));
      p.spin = r.uniform(0.1, 1.0) * p.rolling;
      p.a.angular_velocity = w0 * rho_b / (rho_a + rho_b) * u;
      p.b.angular_velocity = -w0 * rho_a / (rho_a + rho_b) * u;
      const double hold = 10.0, duration = t_stop + 1.0 + hold;
      const core::RunResult result = run(pair_scene(p, in.name, in.dt, duration));
      INFO(in.name << " case " << k << ": m " << p.a.mass << ", " << p.b.mass << ", r "
                   << p.a.radius << ", " << p.b.radius << ", F " << p.force << ", c " << p.rolling
                   << ", W " << w0 << ", n " << p.normal.transpose() << ", u " << u.transpose()
                   << ", stop due at " << t_stop);
      REQUIRE_FALSE(result.instability);
      const auto& tr = result.trajectory;
      auto relative = [&](double t) {
        return (column3(tr, "a.w", t) - column3(tr, "b.w", t)).dot(u);
      };
      const double t1 = tr.at(row_at(tr, 0.2 * t_stop), 0), t2 = tr.at(row_at(tr, 0.8 * t_stop), 0);
      const double measured = (relative(t1) - relative(t2)) / (t2 - t1);
      CHECK(measured == Approx(alpha).epsilon(1e-6));
      worst_a = std::max(worst_a, std::abs(measured / alpha - 1.0));
      CHECK(column3(tr, "touch.rolling.tau", 0.5 * t_stop).dot(u) ==
            Approx(-p.rolling * p.force).epsilon(1e-4));
      const double stop = stick_time(result, "touch.rolling");
      CHECK(stop == Approx(t_stop).margin(1e-6));
      worst_t = std::max(worst_t, std::abs(stop - t_stop));
      // The centres stay put (no friction force): T = 0 by the choice of m_b.
      const double still = std::max((column3(tr, "a.p", duration) - p.a.position).norm(),
                                    (column3(tr, "b.p", duration) - p.b.position).norm());
      CHECK(still < 1e-6 * p.a.radius);
      worst_still = std::max(worst_still, still);
      // Rounding only: the pair's common drift (angular velocity ~1e-13 rad/s left from
      // rounding) turns both frames, and reading b in a's frame adds ~1e-16 a step over 1e5
      // steps (measured up to 2.2e-12; an element that crept would move by its slip, rad/s).
      const double moved = creep(tr, t_stop + 1.0, duration);
      CHECK(moved < 1e-11);
      worst_creep = std::max(worst_creep, moved);
    }
    figure("pair roll", in.name, "relative decel. vs c F (1/J_a + 1/J_b), relative", worst_a);
    figure("pair roll", in.name, "stop (stick event) vs the closed form, s", worst_t);
    figure("pair roll", in.name, "centres' displacement over the run, m", worst_still);
    figure("pair roll", in.name, "creep of b's pose in a's frame, 10 s after the stop",
           worst_creep);
  }
}

TEST_CASE("pair hold: two spheres do not creep under a couple below c N or s N",
          "[rolling][pair]") {
  // A couple (torque on a, the opposite on b) about n loads the spin element, about a
  // tangent u the rolling element; nothing else resists it (the contact point is on the
  // axis, or the couple needs no contact force). The stuck branch, e_dot equal to the
  // relative slip exactly, keeps the relative pose; a leaking anchor would let it turn.
  Random r{std::mt19937(3843)};
  for (const Integrator in : kIntegrators) {
    double worst = 0.0;
    for (int k = 0; k < 4; ++k) {
      Pair p = random_pair(r);
      place(p);
      const bool spin = k % 2 == 0;
      p.spin = r.uniform(0.01, 0.1) * p.a.radius;
      p.rolling = r.uniform(0.01, 0.1) * p.a.radius;
      p.axis = spin ? p.normal : Vec3(r.unit().cross(p.normal).normalized());
      p.torque = r.uniform(0.3, 0.9) * (spin ? p.spin : p.rolling) * p.force;
      const double duration = 11.0;
      const core::RunResult result = run(pair_scene(p, in.name, in.dt, duration));
      INFO(in.name << " case " << k << (spin ? " spin" : " roll") << ": m " << p.a.mass << ", "
                   << p.b.mass << ", r " << p.a.radius << ", " << p.b.radius << ", F " << p.force
                   << ", torque " << p.torque);
      REQUIRE_FALSE(result.instability);
      const Vec3 tau =
          column3(result.trajectory, spin ? "touch.spin.tau" : "touch.rolling.tau", 0.5 * duration);
      CHECK(tau.dot(p.axis) == Approx(-p.torque).epsilon(1e-6));
      const double moved = creep(result.trajectory, 1.0, duration);
      CHECK(moved < 1e-11);  // rounding only, as above
      worst = std::max(worst, moved);
    }
    figure("pair hold", in.name, "creep of b in a's frame from 1 s to 11 s, couple", worst);
  }
}
