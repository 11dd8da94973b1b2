// Boxes touching surfaces at their corners: sliding down a slope at g (sin a - mu cos a)
// without turning, stopping on the floor where the slope ends and holding there without
// drift, held on a slope with mu > tan a, and tipping over an edge when pushed high enough.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <functional>

#include "common.hpp"

using namespace stiction::testing;

namespace {

// Least-squares slope of column `name` against time over [t0, t1].
double rate(const ScenarioRun& run, double t0, double t1, const std::function<double(int)>& value) {
  const auto& tr = run.result.trajectory;
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  for (int r = 0; r < tr.row_count(); ++r) {
    const double t = tr.at(r, 0);
    if (t < t0 || t > t1) continue;
    const double v = value(r);
    n += 1;
    st += t;
    sv += v;
    stt += t * t;
    stv += t * v;
  }
  return (n * stv - st * sv) / (n * stt - st * st);
}

// A box of sides `size` whose bottom face rests on a slope of angle a (normal (sin a, 0,
// cos a), falling toward +x, ending at x = 0 where a floor begins), `distance` up the slope.
std::string slope_scene(double a, double mu, double mass, const stiction::core::Vec3& size,
                        double distance, double duration) {
  const double h = 0.5 * size.z();
  const double cx = -distance * std::cos(a) + h * std::sin(a),
               cz = distance * std::sin(a) + h * std::cos(a);
  const double k = 1e6, b = 2.0 * std::sqrt(k * mass / 4.0);
  std::string s =
      "[simulation]\ndt = 1e-4\noutput_rate = 500.0\nduration = " + num(duration) + "\n";
  s += "[bodies.a_box_with_a_rather_long_name]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = " +
       num(mass) + "\nsize = [" + num(size.x()) + ", " + num(size.y()) + ", " + num(size.z()) +
       "]\nposition = [" + num(cx) + ", 0.0, " + num(cz) + "]\norientation = [" +
       num(std::cos(a / 2)) + ", 0.0, " + num(std::sin(a / 2)) + ", 0.0]\n";
  for (const char* which : {"slope", "floor"}) {
    const bool slope = std::string(which) == "slope";
    s += std::string("[impedances.") + which +
         "]\ntype = \"kikuuwe_contact\"\nbody = \"a_box_with_a_rather_long_name\"\n";
    s += slope ? "normal = [" + num(std::sin(a)) + ", 0.0, " + num(std::cos(a)) +
                     "]\nextent = { axis = [1.0, 0.0, 0.0], max = [0.0, inf] }\nsettle = true\n"
               : "extent = { axis = [1.0, 0.0, 0.0], min = [0.0, -inf] }\n";
    s += "stiffness = " + num(k) + "\ndamping = " + num(b) + "\nmu = " + num(mu) + "\n";
  }
  return s;
}

double along_slope_speed(const ScenarioRun& run, const std::string& body, double a, int r) {
  return std::cos(a) * cell(run, r, run.column(body + ".v.x")) -
         std::sin(a) * cell(run, r, run.column(body + ".v.z"));
}

double max_abs_w(const ScenarioRun& run, const std::string& body, double t0, double t1) {
  double worst = 0.0;
  const auto& tr = run.result.trajectory;
  for (int r = 0; r < tr.row_count(); ++r) {
    if (tr.at(r, 0) < t0 || tr.at(r, 0) > t1) continue;
    for (const char* axis : {"x", "y", "z"})
      worst = std::max(worst, std::abs(tr.at(r, run.column(body + ".w." + axis))));
  }
  return worst;
}

}  // namespace

TEST_CASE("box_slope: slides at g (sin a - mu cos a) without turning, stops on the floor, holds",
          "[contacts][box]") {
  const auto run = run_scenario("box_slope");
  REQUIRE_FALSE(run.result.instability);
  const double a = 20.0 * M_PI / 180.0, mu = 0.2, g = 9.8;
  const double expected = g * (std::sin(a) - mu * std::cos(a));
  const double acc =
      rate(run, 0.2, 1.0, [&](int r) { return along_slope_speed(run, "box", a, r); });
  const double w = max_abs_w(run, "box", 0.2, 1.0);
  std::printf(
      "box_slope: acceleration %.6f m/s^2 (closed form %.6f, error %.2e), max |w| on the slope "
      "%.3e rad/s\n",
      acc, expected, acc / expected - 1.0, w);
  CHECK(acc == Approx(expected).epsilon(5e-3));
  CHECK(w < 1e-6);
  // It reaches the floor (x > 0, resting on its face) and stops.
  const auto& tr = run.result.trajectory;
  double t_stop = -1.0;
  for (int r = 0; r < tr.row_count(); ++r) {
    if (tr.at(r, 0) > 1.2 && tr.at(r, run.column("box.p.x")) > 0.0 &&
        std::abs(tr.at(r, run.column("box.v.x"))) < 1e-6) {
      t_stop = tr.at(r, 0);
      break;
    }
  }
  REQUIRE(t_stop > 0.0);
  REQUIRE(t_stop + 10.5 <= tr.at(tr.row_count() - 1, 0));
  CHECK(run.at("box.p.z", t_stop) == Approx(0.05).margin(1e-4));
  // Closed form on the floor: it arrives at about v1 = a t1 and stops after v1^2 / (2 mu g)
  // (checked loosely: the landing on the floor's edge takes a little speed).
  double drift = 0.0;
  for (const char* axis : {"x", "y", "z"}) {
    const std::string c = std::string("box.p.") + axis;
    drift = std::max(drift, std::abs(run.at(c, t_stop + 10.5) - run.at(c, t_stop + 0.5)));
  }
  std::printf("box_slope: stops at t = %.3f s, x = %.4f m; drift over the next 10 s %.3e m\n",
              t_stop, run.at("box.p.x", t_stop), drift);
  CHECK(drift < 1e-9);
}

TEST_CASE("box_slope_hold: with mu > tan a the settled box never moves", "[contacts][box]") {
  const auto run = run_scenario("box_slope_hold");
  REQUIRE_FALSE(run.result.instability);
  const auto& tr = run.result.trajectory;
  double drift = 0.0;
  for (const char* axis : {"x", "y", "z"}) {
    const auto v = run.values(std::string("box.p.") + axis);
    for (double x : v) drift = std::max(drift, std::abs(x - v.front()));
  }
  std::printf("box_slope_hold: largest displacement over %.1f s: %.3e m\n",
              tr.at(tr.row_count() - 1, 0), drift);
  CHECK(drift < 1e-9);
}

TEST_CASE("box on generated slopes: acceleration within 0.5% of the closed form",
          "[contacts][box]") {
  std::mt19937 rng(20261130);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 3; ++i) {
    const double a = (12.0 + 18.0 * uni(rng)) * M_PI / 180.0;
    const double mu = (0.2 + 0.6 * uni(rng)) * std::tan(a);
    const double mass = 0.5 + 2.0 * uni(rng);
    const stiction::core::Vec3 size(0.1 + 0.2 * uni(rng), 0.1 + 0.2 * uni(rng),
                                    0.05 + 0.1 * uni(rng));
    const auto run = run_text(slope_scene(a, mu, mass, size, 3.0, 0.8));
    REQUIRE_FALSE(run.result.instability);
    const double expected = 9.8 * (std::sin(a) - mu * std::cos(a));
    const std::string body = "a_box_with_a_rather_long_name";
    const double acc =
        rate(run, 0.2, 0.8, [&](int r) { return along_slope_speed(run, body, a, r); });
    INFO("angle " << a << " mu " << mu << " mass " << mass);
    CHECK(acc == Approx(expected).epsilon(5e-3));
    CHECK(max_abs_w(run, body, 0.2, 0.8) < 1e-6);
  }
}

namespace {
// A box of mass m, width w along x (depth d along y), height H, settled on a floor with
// friction mu, pushed along +x by a force_source at a point of its back face at height h
// above the floor: a world-frame horizontal force that follows the point as the box turns,
// ramped up smoothly over 0.3 s to F and then held. It tips about its front edge when the
// force's moment there exceeds the weight's, F h > m g w / 2.
struct Tipping {
  double m, w, d, H, h, mu;
  double threshold() const { return m * 9.8 * (0.5 * w) / h; }
};

struct Tilt {
  double tilt = 0.0;       // largest tilt of the box's z axis (rad)
  double edge_slip = 0.0;  // largest motion of the front bottom edge along x while tilted < 10 deg
};

Tilt tip(const Tipping& b, double force, double duration) {
  const double k = 1e6, damping = 2.0 * std::sqrt(k * b.m / 4.0);
  const std::string body = "a_tall_box_with_a_rather_long_name";
  const std::string text =
      "[simulation]\ndt = 1e-4\noutput_rate = 100.0\nduration = " + num(duration) + "\n[bodies." +
      body + "]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = " + num(b.m) + "\nsize = [" +
      num(b.w) + ", " + num(b.d) + ", " + num(b.H) + "]\nposition = [0.0, 0.0, " + num(0.5 * b.H) +
      "]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"" + body +
      "\"\nstiffness = " + num(k) + "\ndamping = " + num(damping) + "\nmu = " + num(b.mu) +
      "\nsettle = true\n"
      "[impedances.push]\ntype = \"force_source\"\nbody = \"" +
      body + "\"\nframe = \"world\"\npoint = [" + num(-0.5 * b.w) + ", 0.0, " +
      num(b.h - 0.5 * b.H) + "]\nforce = [\"" + num(force) +
      " * (t < 0.3 ? 0.5 - 0.5*cos(_pi*t/0.3) : 1)\", 0, 0]\n";
  const auto run = run_text(text);
  REQUIRE_FALSE(run.result.instability);
  Tilt out;
  const auto px = run.values(body + ".p.x");
  const auto qw = run.values(body + ".q.w"), qx = run.values(body + ".q.x"),
             qy = run.values(body + ".q.y"), qz = run.values(body + ".q.z");
  const Eigen::Vector3d edge(0.5 * b.w, 0.0, -0.5 * b.H);  // the front bottom edge, body frame
  for (std::size_t r = 0; r < qx.size(); ++r) {
    const Eigen::Quaterniond q(qw[r], qx[r], qy[r], qz[r]);
    const double z = 1.0 - 2.0 * (qx[r] * qx[r] + qy[r] * qy[r]);  // the z axis's vertical part
    const double tilt = std::acos(std::clamp(z, -1.0, 1.0));
    out.tilt = std::max(out.tilt, tilt);
    // It turns about the front edge, which does not slide (until it falls past 10 degrees).
    if (tilt < 10.0 * M_PI / 180.0) {
      const double x = px[r] + (q * edge).x();
      out.edge_slip = std::max(out.edge_slip, std::abs(x - 0.5 * b.w));
    }
  }
  return out;
}
}  // namespace

TEST_CASE("box pushed above its centre by a force_source tips when F h exceeds m g w / 2",
          "[contacts][box]") {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 3; ++i) {
    Tipping b{};
    b.m = 0.5 + 2.5 * uni(rng);
    b.w = 0.1 + 0.2 * uni(rng);
    b.d = 0.1 + 0.2 * uni(rng);
    b.H = b.w * (1.2 + 1.3 * uni(rng));
    b.h = b.H * (0.6 + 0.4 * uni(rng));    // above the centre, at most the top
    b.mu = 2.0 * b.w / (2.0 * b.h) + 0.3;  // F* / (m g) = w / (2 h): it does not slide
    const double F = b.threshold();
    const Tilt below = tip(b, 0.97 * F, 1.5), above = tip(b, 1.03 * F, 2.5);
    std::printf(
        "tipping (m %.3f kg, w %.3f m, H %.3f m, h %.3f m, F* %.4f N): 0.97 F* tilts at most "
        "%.3e rad, 1.03 F* tilts %.3f rad; front edge slip %.1e / %.1e m\n",
        b.m, b.w, b.H, b.h, F, below.tilt, above.tilt, below.edge_slip, above.edge_slip);
    INFO("m " << b.m << " w " << b.w << " d " << b.d << " H " << b.H << " h " << b.h);
    CHECK(below.tilt < 1e-3);
    CHECK(above.tilt > 10.0 * M_PI / 180.0);
    CHECK(below.edge_slip < 1e-4);
    CHECK(above.edge_slip < 1e-4);
  }
}
