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
// A tall box (0.2 x 0.2 x 0.4 m, 1 kg) settled on a floor with mu = 1, pushed along +x at
// the middle of its back face's upper part (0.35 m above the floor) by a nearly constant
// force: a spring of 1e-3 N/m stretched by F / k. It tips about its front edge when
// F h > m g w / 2, i.e. F > 2.8 N. Returns the largest tilt of its z axis (rad) over 2 s.
double tip_angle(double force) {
  const double k = 1e-3;
  const std::string text = std::string(
                               "[simulation]\ndt = 1e-4\nduration = 2.0\noutput_rate = 100.0\n"
                               "[bodies.tall]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = "
                               "1.0\nsize = [0.2, 0.2, 0.4]\n"
                               "position = [0.0, 0.0, 0.2]\n"
                               "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = "
                               "\"tall\"\nstiffness = 1e6\ndamping = 1000.0\n"
                               "mu = 1.0\nsettle = true\n"
                               "[impedances.push]\ntype = \"spring_damper\"\nbody = "
                               "\"tall\"\npoint = [-0.1, 0.0, 0.15]\n"
                               "other_point = [0.0, 0.0, 0.0]\nstiffness = ") +
                           num(k) + "\nrest = [" + num(-0.1 - force / k) + ", 0.0, 0.35]\n";
  const auto run = run_text(text);
  REQUIRE_FALSE(run.result.instability);
  double worst = 0.0;
  const auto qx = run.values("tall.q.x"), qy = run.values("tall.q.y");
  for (std::size_t r = 0; r < qx.size(); ++r) {
    const double z = 1.0 - 2.0 * (qx[r] * qx[r] + qy[r] * qy[r]);  // the z axis's vertical part
    worst = std::max(worst, std::acos(std::clamp(z, -1.0, 1.0)));
  }
  return worst;
}
}  // namespace

TEST_CASE("box pushed above its centre tips when F h exceeds m g w / 2, not below",
          "[contacts][box]") {
  const double threshold = 1.0 * 9.8 * 0.1 / 0.35;  // 2.8 N
  const double below = tip_angle(0.97 * threshold), above = tip_angle(1.03 * threshold);
  std::printf("tipping: F = 0.97 F* tilts at most %.3e rad, F = 1.03 F* tilts %.3f rad\n", below,
              above);
  CHECK(below < 1e-3);
  CHECK(above > 0.5);
}
