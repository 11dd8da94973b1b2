// Anisotropic friction on contacts (issue 38 item 2, contact_law.hpp's elliptic limit):
// `mu = [mu_1, mu_2]` along `friction_axes`, against closed forms on generated scenes.
//
// With M = diag(mu_1, mu_2) in the axes' frame, the friction force on a body whose contact
// slides at v is the maximum-dissipation force of the ellipse {f : |M^-1 f| <= N}:
//   F = -N M^2 v / |M v|.
// A block of mass m sliding on a level floor (N = m g) therefore obeys, along the axes,
//   v_1' = -g mu_1^2 v_1 / |M v|,   v_2' = -g mu_2^2 v_2 / |M v|,
// so d ln|v_1| / d ln|v_2| = mu_1^2 / mu_2^2: its velocity keeps
//   |v_1| |v_2|^(-mu_1^2 / mu_2^2) constant
// as it curves toward the axis of lower friction, and decelerates along its path at
// g |M v| / |v| (= g sqrt(mu_1^2 cos^2 phi + mu_2^2 sin^2 phi) at angle phi to axis 1).
// A force along a direction d at angle phi to axis 1 is held while it is at most
//   N mu(phi),  mu(phi) = 1 / |M^-1 d| = 1 / sqrt(cos^2 phi / mu_1^2 + sin^2 phi / mu_2^2),
// so a block stays on a slope of angle theta while tan theta <= mu(phi), phi the angle
// between the downhill direction and axis 1.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "components/impedance/friction_law.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "core/simulation.hpp"
#include "scene/plausibility.hpp"
#include "scene/scene.hpp"
#include "trajectory_rows.hpp"

using namespace stiction;
using testing::column_at;
using testing::row_at;
using core::Vec3;

namespace {

constexpr double kG = 9.8;
constexpr double kK = 1e6;  // contact and friction stiffness (N/m)

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<>(lo, hi)(rng);
}

// A block (point mass, or a box with `box`) on the plane {x : n.x = 0} under gravity -z.
struct Block {
  double mass = 1.0;
  std::string mu = "[0.2, 0.5]";  // the `mu` value as written
  Vec3 normal = Vec3::UnitZ();
  Vec3 axis1 = Vec3::UnitX(), axis2 = Vec3::UnitY();
  bool write_axes = true;
  std::string frame;  // friction_axes_frame, "" for none
  Vec3 v0 = Vec3::Zero();
  std::string push;         // force expressions "[fx, fy, fz]", "" for none
  double belt_speed = 0.0;  // a belt along belt_direction when > 0
  Vec3 belt_direction = Vec3::UnitX();
  bool box = false;
  double yaw = 0.0;  // the box's orientation about z
  const char* integrator = "rk4";
  double dt = 1e-4;
  double duration = 1.0;
  double output_rate = 1000.0;
};

std::string vec(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

std::string block_scene(const Block& b) {
  std::ostringstream s;
  s.precision(17);
  const double damping = 2.0 * std::sqrt(kK * b.mass);  // critical: no ringing when stuck
  const Vec3 n = b.normal.normalized();
  // At rest on the plane: pressed in by its weight's normal part.
  const double points = b.box ? 4.0 : 1.0;
  const double depth = b.mass * kG * n.z() / (points * kK);
  const double half = 0.05;  // the box's half height
  const Vec3 position = (b.box ? half : 0.0) * n - depth * n;
  s << "name = \"generated_anisotropic\"\ngravity = [0.0, 0.0, " << -kG << "]\n"
    << "[simulation]\nintegrator = \"" << b.integrator << "\"\ndt = " << b.dt
    << "\nduration = " << b.duration << "\noutput_rate = " << b.output_rate << "\n";
  if (b.box) {
    s << "[bodies.block]\ntype = \"rigid_body\"\nshape = \"box\"\nsize = [0.4, 0.2, " << 2.0 * half
      << "]\nmass = " << b.mass << "\norientation = [" << std::cos(0.5 * b.yaw) << ", 0.0, 0.0, "
      << std::sin(0.5 * b.yaw) << "]\n";
  } else {
    s << "[bodies.block]\ntype = \"point_mass\"\nmass = " << b.mass << "\n";
  }
  s << "position = " << vec(position) << "\nvelocity = " << vec(b.v0) << "\n"
    << "[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"block\"\n"
    << (b.box ? "" : "radius = 0.0\n") << "normal = " << vec(n) << "\nstiffness = " << kK
    << "\ndamping = " << damping / std::sqrt(points) << "\nmu = " << b.mu << "\n";
  if (b.write_axes) {
    s << "friction_axes = [" << vec(b.axis1) << ", " << vec(b.axis2) << "]\n";
  }
  if (!b.frame.empty()) s << "friction_axes_frame = \"" << b.frame << "\"\n";
  if (b.belt_speed > 0.0) {
    s << "belt_speed = " << b.belt_speed << "\nbelt_direction = " << vec(b.belt_direction) << "\n";
  }
  if (!b.push.empty()) {
    s << "[impedances.push]\ntype = \"force_source\"\nbody = \"block\"\nforce = " << b.push << "\n";
  }
  return s.str();
}

core::RunResult run(const std::string& text) {
  auto scene = scene::load_scene(scene::SceneSource::from_text(text, "generated_anisotropic.toml"));
  return core::simulate(*scene.network, scene.run);
}


Vec3 vec3_at(const core::Trajectory& tr, const std::string& name, int row) {
  return {tr.at(row, *tr.find(name + ".x")), tr.at(row, *tr.find(name + ".y")),
          tr.at(row, *tr.find(name + ".z"))};
}

// The maximum-dissipation force of the elliptic law on a body sliding at v (world), with
// normal force N, mu_1 along a1 and mu_2 along a2 (unit, orthogonal, in the plane).
Vec3 elliptic_force(const Vec3& v, double N, double mu1, double mu2, const Vec3& a1,
                    const Vec3& a2) {
  const double v1 = a1.dot(v), v2 = a2.dot(v);
  const double norm = std::hypot(mu1 * v1, mu2 * v2);
  return -N * (mu1 * mu1 * v1 * a1 + mu2 * mu2 * v2 * a2) / norm;
}

// mu(phi) for a direction at angle phi to axis 1.
double directional_mu(double mu1, double mu2, double phi) {
  return 1.0 / std::hypot(std::cos(phi) / mu1, std::sin(phi) / mu2);
}

// The figures docs/friction_laws.md quotes: printed with STICTION_FIGURES in the environment.
void figure(const char* test, const char* what, double value) {
  if (std::getenv("STICTION_FIGURES") != nullptr) {
    std::printf("%-12s %-52s %.3g\n", test, what, value);
  }
}

std::string mu_text(double mu1, double mu2) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << mu1 << ", " << mu2 << "]";
  return s.str();
}

// A random law on a level floor: mu_1 and mu_2 drawn in [lo, hi], the axes turned by a random
// psi about z, written into b.
struct Law {
  double mu1, mu2, psi;
  Vec3 a1, a2;
};

Law random_law(std::mt19937& rng, Block& b, double lo, double hi) {
  Law l;
  l.mu1 = uniform(rng, lo, hi);
  l.mu2 = uniform(rng, lo, hi);
  b.mu = mu_text(l.mu1, l.mu2);
  l.psi = uniform(rng, 0.0, 2.0 * M_PI);
  l.a1 = Vec3(std::cos(l.psi), std::sin(l.psi), 0.0);
  l.a2 = Vec3(-std::sin(l.psi), std::cos(l.psi), 0.0);
  b.axis1 = l.a1;
  b.axis2 = l.a2;
  return l;
}

}  // namespace

TEST_CASE(
    "anisotropic friction: the elliptic projection is the nearest point of the ellipse, "
    "normal to it",
    "[anisotropic_friction]") {
  std::mt19937 rng(3821);
  double worst_boundary = 0.0, worst_normal = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double a1 = std::pow(10.0, uniform(rng, -3.0, 3.0));
    const double a2 = a1 * std::pow(10.0, uniform(rng, -2.0, 2.0));
    const double angle = uniform(rng, 0.0, 2.0 * M_PI);
    const double radius = std::max(a1, a2) * std::pow(10.0, uniform(rng, -0.3, 4.0));
    Eigen::Vector2d z(radius * std::cos(angle), radius * std::sin(angle));
    if (k % 50 == 0) z.y() = 0.0;                                            // on an axis
    if (std::pow(z.x() / a1, 2) + std::pow(z.y() / a2, 2) <= 1.0) continue;  // inside
    const Eigen::Vector2d x = components::nearest_on_ellipse(z, a1, a2);
    INFO("k " << k << ": a " << a1 << ", " << a2 << ", z " << z.transpose() << ", x "
              << x.transpose());
    // On the boundary.
    const double level = std::hypot(x.x() / a1, x.y() / a2);
    CHECK(std::abs(level - 1.0) <= 1e-12);
    // z - x along the outward normal (x_1 / a_1^2, x_2 / a_2^2): the nearest point.
    const Eigen::Vector2d normal(x.x() / (a1 * a1), x.y() / (a2 * a2));
    const Eigen::Vector2d d = z - x;
    const double cross = (d.x() * normal.y() - d.y() * normal.x()) / (d.norm() * normal.norm());
    CHECK(std::abs(cross) <= 1e-9);
    CHECK(d.dot(normal) > 0.0);
    // No point of the boundary nearer (sampled).
    double nearest = 1e300;
    for (int i = 0; i < 3600; ++i) {
      const double s = 2.0 * M_PI * i / 3600.0;
      nearest = std::min(nearest, (z - Eigen::Vector2d(a1 * std::cos(s), a2 * std::sin(s))).norm());
    }
    CHECK(d.norm() <= nearest * (1.0 + 1e-12));
    worst_boundary = std::max(worst_boundary, std::abs(level - 1.0));
    worst_normal = std::max(worst_normal, std::abs(cross));
  }
  figure("projection", "|level - 1| on the boundary (max)", worst_boundary);
  figure("projection", "sine between z - x and the normal (max)", worst_normal);
}

TEST_CASE(
    "anisotropic friction: a contact sliding steadily at v carries -N M^2 v / |M v| to "
    "rounding, and holds exactly inside the ellipse",
    "[anisotropic_friction]") {
  // A steady slide has the anchor moving with the contact point (w = v, e_dot = 0): the
  // spring then holds e = -F / Kt... in the element's sign, u = -(force on the body) and the
  // element's f = Kt e. Given v, the state e = f(v) / Kt with f(v) = N M^2 v / |M v| (the
  // force the body exerts on the element) must give back exactly that force and e_dot = 0.
  std::mt19937 rng(3826);
  double worst = 0.0, worst_rate = 0.0;
  for (int k = 0; k < 500; ++k) {
    components::KikuuweContactParams p;
    p.stiffness = std::pow(10.0, uniform(rng, 4.0, 7.0));
    p.damping = uniform(rng, 1.0, 500.0);
    p.mu = uniform(rng, 0.05, 1.0);
    p.mu_2 = uniform(rng, 0.05, 1.0);
    const double psi = uniform(rng, 0.0, 2.0 * M_PI);
    p.friction_axis = Vec3(std::cos(psi), std::sin(psi), uniform(rng, -1.0, 1.0));  // z: dropped
    const components::KikuuweContact contact("c", p);
    const Vec3 a1(std::cos(psi), std::sin(psi), 0.0), a2(-std::sin(psi), std::cos(psi), 0.0);
    const double depth = uniform(rng, 1e-6, 1e-4);
    const double N = p.stiffness * depth;  // at zero normal speed
    const double phi = uniform(rng, 0.0, 2.0 * M_PI),
                 speed = std::pow(10.0, uniform(rng, -4.0, 1.0));
    const Vec3 v = speed * (std::cos(phi) * a1 + std::sin(phi) * a2);
    const Vec3 on_body = elliptic_force(v, N, p.mu, p.mu_2, a1, a2);
    core::Vec x_hat(6), y(2), u(3), y_dot(2);
    x_hat << 0.0, 0.0, -depth, v.x(), v.y(), 0.0;
    y << -on_body.x() / p.stiffness, -on_body.y() / p.stiffness;  // t1, t2 = x, y
    const double tau = uniform(rng, 0.0, 1e-3);
    contact.evaluate(0.0, x_hat, y, tau, u, y_dot);
    INFO("k " << k << ": mu " << p.mu << ", " << p.mu_2 << ", psi " << psi << ", phi " << phi
              << ", |v| " << speed);
    const Vec3 got = -Vec3(u.head<3>()) - N * Vec3::UnitZ();
    const double error = (got - on_body).norm() / on_body.norm();
    CHECK(error <= 1e-12);
    // e_dot = 0: relative to the speed.
    CHECK(y_dot.norm() <= 1e-9 * speed);
    CHECK(contact.regime(x_hat, y, tau) == 2);
    worst = std::max(worst, error);
    worst_rate = std::max(worst_rate, y_dot.norm() / speed);
    // Inside the ellipse it is stuck: e_dot is v bit for bit.
    core::Vec y_in = 0.999 * y;
    x_hat.segment<3>(3).setZero();
    contact.evaluate(0.0, x_hat, y_in, tau, u, y_dot);
    CHECK(y_dot[0] == 0.0);
    CHECK(y_dot[1] == 0.0);
    CHECK(contact.regime(x_hat, y_in, tau) == 1);
  }
  figure("steady", "force vs -N M^2 v / |M v|, relative (max)", worst);
  figure("steady", "|e_dot| / |v| in a steady slide (max)", worst_rate);
}

TEST_CASE(
    "anisotropic friction: a block sliding at angle phi to the first axis decelerates with "
    "the elliptic law's force, for 20 random phi",
    "[anisotropic_friction]") {
  std::mt19937 rng(3822);
  double worst_force = 0.0, worst_invariant = 0.0, worst_decel = 0.0, worst_anchor = 0.0;
  double worst_lag = 0.0;
  for (int k = 0; k < 20; ++k) {
    Block b;
    b.mass = uniform(rng, 0.3, 5.0);
    // The axes turned by psi about z, the launch at phi to axis 1.
    const Law law = random_law(rng, b, 0.1, 0.8);
    const double mu1 = law.mu1, mu2 = law.mu2, psi = law.psi;
    const Vec3 a1 = law.a1, a2 = law.a2;
    const double phi = uniform(rng, 0.0, 2.0 * M_PI);
    if (k % 2 == 1) b.axis2 = -a2;  // the ellipse does not care about the sign
    const double speed = uniform(rng, 0.5, 2.0);
    b.v0 = speed * (std::cos(phi) * a1 + std::sin(phi) * a2);
    // Slides until about a third of its speed is left (the slower decay is g min mu).
    b.duration = 0.6 * speed / (kG * std::max(mu1, mu2));
    const core::RunResult r = run(block_scene(b));
    INFO("case " << k << ": m " << b.mass << ", mu " << b.mu << ", psi " << psi << ", phi " << phi
                 << ", v0 " << speed);
    REQUIRE_FALSE(r.instability);
    const auto& tr = r.trajectory;
    // From 20 ms (the friction spring starts relaxed and loads within about 1 ms).
    const int row0 = row_at(tr, 0.02);
    const Vec3 v_ref = vec3_at(tr, "block.v", row0);
    const double exponent = mu1 * mu1 / (mu2 * mu2);
    const auto invariant = [&](const Vec3& v) {
      return std::log(std::abs(a1.dot(v))) - exponent * std::log(std::abs(a2.dot(v)));
    };
    int checked = 0;
    const int e0 = *tr.find("ground.e.0"), e1 = *tr.find("ground.e.1");
    const int stride = std::max(1, (tr.row_count() - row0) / 20);
    for (int row = row0; row + 1 < tr.row_count(); row += stride) {
      const Vec3 v = vec3_at(tr, "ground.slip", row);
      const Vec3 f = vec3_at(tr, "ground.f", row);
      const double N = tr.at(row, *tr.find("ground.n_force"));
      const Vec3 f_t = f - f.dot(Vec3::UnitZ()) * Vec3::UnitZ();
      // The law acts on the anchor's velocity w: the row's force is evaluated with tau = dt,
      // where z = (Bt + dt Kt) v + Kt e and w = (z - f) / (Bt + dt Kt), f = -f_t the force on
      // the element (e along t1, t2 = x, y here). At w the force is the elliptic law's to
      // rounding.
      const Vec3 e(tr.at(row, e0), tr.at(row, e1), 0.0);
      const double BtK = 2.0 * std::sqrt(kK * b.mass) + b.dt * kK;
      const Vec3 w = v + (kK * e + f_t) / BtK;
      const Vec3 at_w = elliptic_force(w, N, mu1, mu2, a1, a2);
      const double anchor_error = (f_t - at_w).norm() / at_w.norm();
      CHECK(anchor_error <= 1e-9);
      // e's rate, by a central difference of the rows.
      const double h = tr.at(row + 1, 0) - tr.at(row - 1, 0);
      const Vec3 e_dot((tr.at(row + 1, e0) - tr.at(row - 1, e0)) / h,
                       (tr.at(row + 1, e1) - tr.at(row - 1, e1)) / h, 0.0);
      worst_anchor = std::max(worst_anchor, anchor_error);
      // At the body's own slip the two differ by the spring's rate of stretch, |e_dot| / |v|
      // relative (about m g mu omega / (K |v|) as the path turns at omega), which the law's
      // slope can amplify by up to (mu_max / mu_min)^2.
      const Vec3 expected = elliptic_force(v, N, mu1, mu2, a1, a2);
      const double lag = e_dot.norm() / v.norm();
      const double gain = std::pow(std::max(mu1, mu2) / std::min(mu1, mu2), 2);
      const double force_error = (f_t - expected).norm() / expected.norm();
      CHECK(force_error <= 3e-5 + 2.0 * gain * lag);
      worst_force = std::max(worst_force, force_error);
      worst_lag = std::max(worst_lag, lag);
      // Deceleration along the path: g |M v| / |v| (with N = m g to the normal bounce).
      const double along = -f_t.dot(v.normalized()) / b.mass;
      const double due = kG * std::hypot(mu1 * a1.dot(v), mu2 * a2.dot(v)) / v.norm();
      worst_decel = std::max(worst_decel, std::abs(along / due - 1.0));
      CHECK(along == Approx(due).epsilon(3e-5 + 2.0 * gain * lag));
      // The hodograph's invariant, while both components are well above rounding.
      const Vec3 body_v = vec3_at(tr, "block.v", row);
      if (std::abs(a1.dot(body_v)) > 1e-3 * speed && std::abs(a2.dot(body_v)) > 1e-3 * speed) {
        const double drift = std::abs(invariant(body_v) - invariant(v_ref));
        // The lag above bends the path a little too; a law with the force along v (radial
        // projection) would keep v's direction and drift by |1 - exponent| ln(v0 / v), O(0.1-1).
        CHECK(drift <= 2e-3 * (1.0 + exponent));
        worst_invariant = std::max(worst_invariant, drift / (1.0 + exponent));
      }
      ++checked;
    }
    CHECK(checked > 5);
  }
  figure("slide", "force vs the law at the anchor's w, relative (max)", worst_anchor);
  figure("slide", "friction force vs -N M^2 v / |M v|, relative (max)", worst_force);
  figure("slide", "|e_dot| / |v|, the friction spring's lag (max)", worst_lag);
  figure("slide", "deceleration along the path vs g |M v| / |v| (max)", worst_decel);
  figure("slide", "ln|v1| - (mu1/mu2)^2 ln|v2| drift / (1 + (mu1/mu2)^2) (max)", worst_invariant);
}

TEST_CASE(
    "anisotropic friction: a block on a slope within the elliptic limit stays put to "
    "rounding, and a force ramp breaks it away at N mu(phi) within one step",
    "[anisotropic_friction]") {
  std::mt19937 rng(3823);
  double worst_drift = 0.0;
  for (int k = 0; k < 6; ++k) {
    Block b;
    b.mass = uniform(rng, 0.3, 5.0);
    const double mu1 = uniform(rng, 0.2, 0.8), mu2 = uniform(rng, 0.2, 0.8);
    b.mu = mu_text(mu1, mu2);
    // The slope: normal tilted by theta from z toward -x, downhill d = (cos, 0, -sin)... in
    // the plane; the axes at phi from downhill.
    const double phi = uniform(rng, 0.0, 2.0 * M_PI);
    const double theta = std::atan(uniform(rng, 0.3, 0.95) * directional_mu(mu1, mu2, phi));
    b.normal = Vec3(std::sin(theta), 0.0, std::cos(theta));
    const Vec3 downhill(std::cos(theta), 0.0, -std::sin(theta));
    const Vec3 across = b.normal.cross(downhill);
    b.axis1 = std::cos(phi) * downhill + std::sin(phi) * across;
    b.axis2 = b.normal.cross(b.axis1);
    b.duration = 11.0;
    b.output_rate = 10.0;
    const core::RunResult r = run(block_scene(b));
    INFO("case " << k << ": m " << b.mass << ", mu " << b.mu << ", phi " << phi << ", tan theta "
                 << std::tan(theta) << " <= mu(phi) " << directional_mu(mu1, mu2, phi));
    REQUIRE_FALSE(r.instability);
    const auto& tr = r.trajectory;
    const double drift =
        (vec3_at(tr, "block.p", row_at(tr, 11.0)) - vec3_at(tr, "block.p", row_at(tr, 1.0))).norm();
    CHECK(drift < 1e-12);
    worst_drift = std::max(worst_drift, drift);
    // Held by friction: the force along the slope carries the weight's part.
    const Vec3 f = vec3_at(tr, "ground.f", tr.row_count() - 1);
    CHECK(f.dot(downhill) == Approx(-b.mass * kG * std::sin(theta)).epsilon(1e-9));
  }
  figure("hold", "drift from 1 s to 11 s on a slope, m (max)", worst_drift);

  // Breakaway: a push r t along d at phi to axis 1 on a level floor breaks the block away
  // when r t = m g mu(phi). The anchor (position less the spring's stretch) holds exactly
  // until then.
  double worst_early = 0.0, worst_late = 0.0;
  for (const char* integrator : {"rk4", "implicit"}) {
    for (int k = 0; k < 4; ++k) {
      Block b;
      b.integrator = integrator;
      b.dt = std::string(integrator) == "implicit" ? 1e-3 : 1e-4;
      b.output_rate = 1.0 / b.dt;
      b.mass = uniform(rng, 0.3, 5.0);
      const Law law = random_law(rng, b, 0.1, 0.8);
      const double mu1 = law.mu1, mu2 = law.mu2;
      const double phi = uniform(rng, 0.0, 2.0 * M_PI);
      const Vec3 d = std::cos(phi) * b.axis1 + std::sin(phi) * b.axis2;
      const double limit = b.mass * kG * directional_mu(mu1, mu2, phi);
      const double t_break = uniform(rng, 0.3, 0.8);
      const double rate = limit / t_break;
      std::ostringstream push;
      push.precision(17);
      push << "[\"" << rate * d.x() << " * t\", \"" << rate * d.y() << " * t\", 0.0]";
      b.push = push.str();
      b.duration = t_break + 0.05;
      const core::RunResult r = run(block_scene(b));
      INFO(integrator << " case " << k << ": m " << b.mass << ", mu " << b.mu << ", phi " << phi
                      << ", breakaway due at " << t_break << " s (" << limit << " N)");
      REQUIRE_FALSE(r.instability);
      const auto& tr = r.trajectory;
      const auto anchor = [&](int row) {
        return Eigen::Vector2d(
            tr.at(row, *tr.find("block.p.x")) - tr.at(row, *tr.find("ground.e.0")),
            tr.at(row, *tr.find("block.p.y")) - tr.at(row, *tr.find("ground.e.1")));
      };
      int first_moved = -1;
      for (int row = 1; row < tr.row_count() && first_moved < 0; ++row) {
        if ((anchor(row) - anchor(0)).norm() > 1e-13) first_moved = row;
      }
      REQUIRE(first_moved > 0);
      const double t_moved = tr.at(first_moved, 0);
      // Within a step of it: at rest the trial force z = (Bt + tau Kt) v + Kt e exceeds the
      // push by tau r (the spring-damper carries the push, the step adds tau Kt v, v = r / Kt),
      // so the step that ends at t_moved may see the limit up to one step early.
      CHECK(t_moved >= t_break - b.dt * (1.0 + 1e-6));
      CHECK(t_moved <= t_break + 2.0 * b.dt);
      worst_early = std::max(worst_early, (t_break - t_moved) / b.dt);
      worst_late = std::max(worst_late, (t_moved - t_break) / b.dt);
      // Slid away by the end.
      CHECK(vec3_at(tr, "block.v", tr.row_count() - 1).norm() > 1e-4);
    }
  }
  figure("breakaway", "first moved row before r t = N mu(phi), steps (max)", worst_early);
  figure("breakaway", "first moved row after r t = N mu(phi), steps (max)", worst_late);
}

TEST_CASE(
    "anisotropic friction: a block dropped on a belt meets the elliptic law's force at its "
    "slip relative to the belt, and is carried along",
    "[anisotropic_friction]") {
  // On a belt at constant speed the slip is the velocity relative to the belt (a Galilean
  // frame): the block starts at rest, slips at -v_b d, and the law acts on that slip.
  std::mt19937 rng(3827);
  double worst = 0.0;
  for (int k = 0; k < 4; ++k) {
    Block b;
    b.mass = uniform(rng, 0.3, 3.0);
    const Law law = random_law(rng, b, 0.1, 0.8);
    const double mu1 = law.mu1, mu2 = law.mu2, psi = law.psi;
    const Vec3 a1 = law.a1, a2 = law.a2;
    const double phi = uniform(rng, 0.0, 2.0 * M_PI);
    b.belt_speed = uniform(rng, 0.3, 1.0);
    b.belt_direction = std::cos(phi) * a1 + std::sin(phi) * a2;
    b.duration = 3.0 * b.belt_speed / (kG * std::min(mu1, mu2));
    const core::RunResult r = run(block_scene(b));
    INFO("case " << k << ": m " << b.mass << ", mu " << b.mu << ", psi " << psi << ", phi " << phi
                 << ", belt " << b.belt_speed);
    REQUIRE_FALSE(r.instability);
    const auto& tr = r.trajectory;
    const int e0 = *tr.find("ground.e.0"), e1 = *tr.find("ground.e.1");
    int sliding = 0;
    for (int row = row_at(tr, 0.02); row < tr.row_count(); ++row) {
      const Vec3 slip = vec3_at(tr, "ground.slip", row);
      if (slip.norm() < 0.05 * b.belt_speed) break;  // nearly carried
      const Vec3 f = vec3_at(tr, "ground.f", row);
      const Vec3 f_t(f.x(), f.y(), 0.0);
      const double N = tr.at(row, *tr.find("ground.n_force"));
      const Vec3 e(tr.at(row, e0), tr.at(row, e1), 0.0);
      const Vec3 w = slip + (kK * e + f_t) / (2.0 * std::sqrt(kK * b.mass) + b.dt * kK);
      const Vec3 at_w = elliptic_force(w, N, mu1, mu2, a1, a2);
      const double error = (f_t - at_w).norm() / at_w.norm();
      CHECK(error <= 1e-9);
      worst = std::max(worst, error);
      ++sliding;
    }
    CHECK(sliding > 10);
    // Carried by the belt in the end.
    const Vec3 v = vec3_at(tr, "block.v", tr.row_count() - 1);
    CHECK((v - b.belt_speed * b.belt_direction).norm() <= 1e-6 * b.belt_speed);
  }
  figure("belt", "force vs the law at the anchor's slip, relative (max)", worst);
}

TEST_CASE(
    "anisotropic friction: body-fixed axes follow the body (a yawed box slides as with the "
    "world axes turned alike)",
    "[anisotropic_friction]") {
  std::mt19937 rng(3824);
  double worst = 0.0;
  for (int k = 0; k < 3; ++k) {
    Block b;
    b.box = true;
    b.mass = uniform(rng, 0.5, 3.0);
    const double mu1 = uniform(rng, 0.1, 0.3), mu2 = uniform(rng, 0.4, 0.8);
    b.mu = mu_text(mu1, mu2);
    b.yaw = uniform(rng, 0.0, 2.0 * M_PI);
    const double phi = uniform(rng, 0.0, 2.0 * M_PI), speed = uniform(rng, 0.5, 1.5);
    const Vec3 a1(std::cos(b.yaw), std::sin(b.yaw), 0.0),
        a2(-std::sin(b.yaw), std::cos(b.yaw), 0.0);
    b.v0 = speed * (std::cos(phi) * a1 + std::sin(phi) * a2);
    b.duration = 0.4 * speed / (kG * mu2);
    Block body = b, world = b, unturned = b;
    body.frame = "body";
    body.axis1 = Vec3::UnitX();
    body.axis2 = Vec3::UnitY();
    world.frame = "world";
    world.axis1 = a1;
    world.axis2 = a2;
    unturned.axis1 = Vec3::UnitX();  // world axes that ignore the yaw
    unturned.axis2 = Vec3::UnitY();
    INFO("case " << k << ": m " << b.mass << ", mu " << b.mu << ", yaw " << b.yaw << ", phi "
                 << phi);
    const core::RunResult rb = run(block_scene(body));
    const core::RunResult rw = run(block_scene(world));
    const core::RunResult ru = run(block_scene(unturned));
    REQUIRE_FALSE(rb.instability);
    REQUIRE_FALSE(rw.instability);
    const int last = rb.trajectory.row_count() - 1;
    const Vec3 pb = vec3_at(rb.trajectory, "block.p", last);
    const Vec3 pw = vec3_at(rw.trajectory, "block.p", last);
    const Vec3 pu = vec3_at(ru.trajectory, "block.p", last);
    const Vec3 start = vec3_at(rb.trajectory, "block.p", 0);
    const double travel = (pw - start).norm();
    CHECK((pb - pw).norm() <= 1e-6 * travel);
    worst = std::max(worst, (pb - pw).norm() / travel);
    // Not by chance: axes that do not turn with the box give another path (unless the yaw
    // is a multiple of a half turn, which the draw avoids).
    if (std::abs(std::sin(b.yaw)) > 0.2) CHECK((pu - pw).norm() > 1e-3 * travel);
  }
  figure("body_axes", "end position, body vs turned world axes, relative (max)", worst);
}

TEST_CASE("anisotropic friction: mu = [m, m] is mu = m bit for bit, with or without friction_axes",
          "[anisotropic_friction]") {
  std::mt19937 rng(3825);
  for (const char* integrator : {"rk4", "implicit"}) {
    for (int k = 0; k < 2; ++k) {
      Block b;
      b.integrator = integrator;
      b.dt = std::string(integrator) == "implicit" ? 1e-3 : 1e-4;
      b.mass = uniform(rng, 0.5, 3.0);
      const double mu = uniform(rng, 0.1, 0.6);
      b.duration = 2.0;
      // A push that swings round: the block sticks and slips in changing directions.
      std::ostringstream push;
      push.precision(17);
      const double amplitude = 1.5 * mu * b.mass * kG;
      push << "[\"" << amplitude << " * sin(6.283 * t)\", \"" << 0.3 * amplitude
           << " * cos(4.1 * t)\", 0.0]";
      b.push = push.str();
      b.box = k == 1;
      Block plain = b, pair = b;
      std::ostringstream number;
      number.precision(17);
      number << mu;
      plain.mu = number.str();
      plain.write_axes = false;
      pair.mu = mu_text(mu, mu);
      pair.axis1 = Vec3(0.6, 0.8, 0.0);
      pair.axis2 = Vec3(-0.8, 0.6, 0.0);
      INFO(integrator << (b.box ? " box" : " point mass") << ", mu " << mu);
      const core::RunResult a = run(block_scene(plain));
      const core::RunResult c = run(block_scene(pair));
      const auto &p = a.trajectory, &s = c.trajectory;
      REQUIRE(p.row_count() == s.row_count());
      REQUIRE(p.columns() == s.columns());
      bool identical = true;
      for (int row = 0; row < p.row_count(); ++row) {
        for (int col = 0; col < p.column_count(); ++col) {
          identical = identical && p.at(row, col) == s.at(row, col);
        }
      }
      CHECK(identical);
      // Both branches of the law were compared: it stuck and it slid.
      int held = 0, moved = 0;
      for (int row = 1; row < p.row_count(); ++row) {
        const double speed = vec3_at(p, "block.v", row).norm();
        held += speed < 1e-4 ? 1 : 0;
        moved += speed > 1e-2 ? 1 : 0;
      }
      CHECK(held > 20);
      CHECK(moved > 20);
    }
  }
}

TEST_CASE(
    "anisotropic friction: the scene keys are checked, with file, line and key in the "
    "message",
    "[anisotropic_friction]") {
  struct Bad {
    std::string lines;  // appended to the contact's table
    std::string key;    // named in the message
    std::string text;   // and this
    bool pair = false;  // mu given to a contact between two bodies
  };
  const Bad bads[] = {
      {"mu = [0.2, 0.5, 0.1]\n", "mu", "got 3 numbers"},
      {"mu = [0.2]\n", "mu", "got 1 numbers"},
      {"mu = [0.2, 0.0]\n", "mu", "must be > 0"},
      {"mu = [-0.2, 0.3]\n", "mu", "must be > 0"},
      {"mu = [0.2, \"x\"]\n", "mu", "expected a number"},
      {"mu = [0.2, 0.5]\nfriction_axes = [[1.0, 0.0, 0.0], [0.5, 1.0, 0.0]]\n", "friction_axes",
       "orthogonal"},
      {"mu = [0.2, 0.5]\nfriction_axes = [[1.0, 0.0, 0.1], [0.0, 1.0, 0.0]]\n", "friction_axes",
       "not in the surface"},
      {"mu = [0.2, 0.5]\nfriction_axes = [[1.0, 0.0, 0.0]]\n", "friction_axes",
       "expected two directions"},
      {"mu = [0.2, 0.5]\nfriction_axes = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n", "friction_axes",
       "non-zero"},
      {"mu = 0.3\nfriction_axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n", "friction_axes",
       "needs `mu = [mu_1, mu_2]`"},
      {"mu = [0.2, 0.5]\nfriction_axes_frame = \"surface\"\n", "friction_axes_frame",
       "\"world\" or \"body\""},
      {"mu = [0.2, 0.5]\nfriction_axes_frame = \"body\"\n"
       "friction_axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n",
       "friction_axes_frame", "point_mass"},
      {"mu = [0.2, 0.5]\nmu_static = 0.6\n", "mu_static", "not defined with anisotropic"},
      {"mu = [0.2, 0.5]\nstribeck_velocity = 0.01\n", "stribeck_velocity",
       "not defined with anisotropic"},
      {"mu = [0.2, 0.5]\nviscous = 2.0\n", "viscous", "not defined with anisotropic"},
      {"mu = [0.2, 0.2]\nmu_static = 0.1\n", "mu_static", "must be >= `mu`"},
      {"mu = [0.2, 0.5]\n", "mu", "needs a surface", true},
  };
  for (const Bad& bad : bads) {
    std::string text;
    if (bad.pair) {
      text =
          "name = \"generated_anisotropic\"\n[simulation]\nduration = 0.01\n"
          "[bodies.a]\ntype = \"rigid_body\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n"
          "[bodies.b]\ntype = \"rigid_body\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n"
          "position = [0.3, 0.0, 0.0]\n"
          "[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"a\"\nother = \"b\"\n";
    } else {
      Block b;
      b.write_axes = false;
      b.duration = 0.01;
      text = block_scene(b);
      // Drop the generated `mu` line: the case gives its own.
      const auto mu_line = text.find("mu = [0.2, 0.5]\n");
      REQUIRE(mu_line != std::string::npos);
      text.erase(mu_line, std::string("mu = [0.2, 0.5]\n").size());
    }
    // The key's line in the appended text.
    const int first = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
    const auto at = bad.lines.find(bad.key + " =");
    REQUIRE(at != std::string::npos);
    const int line =
        first + static_cast<int>(
                    std::count(bad.lines.begin(), bad.lines.begin() + static_cast<long>(at), '\n'));
    text += bad.lines;
    INFO(bad.lines);
    try {
      run(text);
      FAIL("accepted");
    } catch (const scene::InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find("generated_anisotropic.toml:" + std::to_string(line) + ":") !=
            std::string::npos);
      CHECK(what.find("ground." + bad.key) != std::string::npos);
      CHECK(what.find(bad.text) != std::string::npos);
    }
  }
}

TEST_CASE("anisotropic friction: the plausibility check reads the larger of [mu_1, mu_2]",
          "[anisotropic_friction]") {
  for (const char* mu : {"[0.3, 25.0]", "[25.0, 0.3]", "[0.3, 0.6]"}) {
    Block b;
    b.mu = mu;
    b.duration = 0.01;
    auto scene = scene::load_scene(
        scene::SceneSource::from_text(block_scene(b), "generated_anisotropic.toml"));
    const auto warnings = scene::plausibility_warnings(scene);
    const bool warned = std::any_of(warnings.begin(), warnings.end(),
                                    [](const auto& w) { return w.key == "impedances.ground.mu"; });
    INFO(mu);
    CHECK(warned == (std::string(mu) != "[0.3, 0.6]"));
  }
}
