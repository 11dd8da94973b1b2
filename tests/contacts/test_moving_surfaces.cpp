// Moving surfaces: the stick-slip oscillator on a belt (period 2 pi / omega, centre F / k,
// amplitude v_b / omega) and a sphere on a tilting plane (slips where tan = 7/2 mu).
#include <catch2/catch.hpp>
#include <cstdio>

#include "common.hpp"

using namespace stiction::testing;

namespace {

struct Oscillation {
  double period, centre, amplitude;
};

// Extremes of x after t0 (parabola through the three samples around each), averaged.
Oscillation oscillation(const ScenarioRun& run, const std::string& column, double t0) {
  const auto& tr = run.result.trajectory;
  const int c = run.column(column);
  std::vector<double> max_t, max_v, min_v;
  for (int r = 1; r + 1 < tr.row_count(); ++r) {
    if (tr.at(r, 0) < t0) continue;
    const double a = tr.at(r - 1, c), b = tr.at(r, c), d = tr.at(r + 1, c);
    const bool is_max = b > a && b >= d, is_min = b < a && b <= d;
    if (!is_max && !is_min) continue;
    const double h = tr.at(r + 1, 0) - tr.at(r, 0);
    const double den = a - 2.0 * b + d;
    const double s = den != 0.0 ? 0.5 * (a - d) / den : 0.0;
    const double peak = b - 0.25 * (a - d) * s;
    if (is_max) {
      max_t.push_back(tr.at(r, 0) + s * h);
      max_v.push_back(peak);
    } else {
      min_v.push_back(peak);
    }
  }
  REQUIRE(max_t.size() >= 3);
  REQUIRE(min_v.size() >= 3);
  double hi = 0, lo = 0;
  for (double v : max_v) hi += v / max_v.size();
  for (double v : min_v) lo += v / min_v.size();
  return {(max_t.back() - max_t.front()) / (max_t.size() - 1), 0.5 * (hi + lo), 0.5 * (hi - lo)};
}

void check_belt(const ScenarioRun& run, const std::string& mass_name, double m, double k, double mu,
                double vb) {
  REQUIRE_FALSE(run.result.instability);
  const double omega = std::sqrt(k / m), force = mu * m * 9.8;
  // After the first ride with the belt (x = v_b t up to F / k) and a quarter period.
  const double t0 = force / (k * vb) + 0.5 * M_PI / omega;
  const Oscillation o = oscillation(run, mass_name + ".p.x", t0);
  std::printf(
      "belt: period %.6f s (2 pi/omega %.6f), centre %.6f m (F/k %.6f), amplitude %.6f m "
      "(v_b/omega %.6f)\n",
      o.period, 2 * M_PI / omega, o.centre, force / k, o.amplitude, vb / omega);
  CHECK(o.period == Approx(2 * M_PI / omega).epsilon(5e-3));
  CHECK(o.centre == Approx(force / k).epsilon(1e-2));
  CHECK(o.amplitude == Approx(vb / omega).epsilon(1e-2));
  // Its speed touches the belt's once per period and never exceeds it (after the start,
  // where the friction spring overshoots while the belt drags the resting mass up to speed).
  double fastest = -1e9;
  const auto t = run.values("t"), v = run.values(mass_name + ".v.x");
  for (std::size_t r = 0; r < t.size(); ++r) {
    if (t[r] > t0) fastest = std::max(fastest, v[r]);
  }
  CHECK(fastest == Approx(vb).epsilon(1e-3));
}

// Time, plane angle and the friction ratio |f_t| / N at the first sample (after 0.05 s)
// where the contact's friction reaches mu N: the onset of slip.
double slip_onset_angle(const ScenarioRun& run, const std::string& contact, double mu) {
  const auto& tr = run.result.trajectory;
  for (int r = 0; r < tr.row_count(); ++r) {
    if (tr.at(r, 0) < 0.05) continue;
    const double th = tr.at(r, run.column(contact + ".angle"));
    const double n_force = tr.at(r, run.column(contact + ".n_force"));
    const stiction::core::Vec3 f(tr.at(r, run.column(contact + ".f.x")),
                                 tr.at(r, run.column(contact + ".f.y")),
                                 tr.at(r, run.column(contact + ".f.z")));
    const stiction::core::Vec3 n(std::sin(th), 0.0, std::cos(th));
    const double ratio = (f - n.dot(f) * n).norm() / n_force;
    if (n_force > 0.0 && ratio >= mu * (1.0 - 1e-9)) return th;
  }
  return -1.0;
}

}  // namespace

TEST_CASE("belt_oscillator: period 2 pi/omega, centre F/k, amplitude v_b/omega",
          "[contacts][belt]") {
  check_belt(run_scenario("belt_oscillator"), "mass", 1.0, 100.0, 0.3, 0.2);
}

TEST_CASE("belt oscillators with generated parameters", "[contacts][belt]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 2; ++i) {
    const double m = 0.5 + uni(rng), k = 50.0 + 150.0 * uni(rng), mu = 0.2 + 0.3 * uni(rng),
                 vb = 0.05 + 0.2 * uni(rng);
    const double period = 2 * M_PI / std::sqrt(k / m);
    const std::string text =
        "[simulation]\ndt = 1e-4\nduration = " + num(mu * m * 9.8 / (k * vb) + 5.0 * period) +
        "\n[bodies.slider_on_a_conveyor]\ntype = \"point_mass\"\nmass = " + num(m) +
        "\n[impedances.conveyor_surface_number_1]\ntype = \"kikuuwe_contact\"\nbody = "
        "\"slider_on_a_conveyor\"\n"
        "belt_speed = \"" +
        num(vb) + "\"\nstiffness = 1e6\ndamping = " + num(2.0 * std::sqrt(1e6 * m)) +
        "\nmu = " + num(mu) +
        "\nsettle = true\n[impedances.spring]\ntype = \"spring_damper\"\nbody = "
        "\"slider_on_a_conveyor\"\n"
        "stiffness = " +
        num(k) + "\n";
    INFO(text);
    check_belt(run_text(text), "slider_on_a_conveyor", m, k, mu, vb);
  }
}

TEST_CASE("tilting_plane: the sphere slips where tan(angle) = 7/2 mu", "[contacts][tilt]") {
  const auto run = run_scenario("tilting_plane");
  REQUIRE_FALSE(run.result.instability);
  const double onset = slip_onset_angle(run, "plane", 0.04);
  const double expected = std::atan(3.5 * 0.04);
  std::printf("tilting_plane: slips at %.4f deg (closed form %.4f deg)\n", onset * 180 / M_PI,
              expected * 180 / M_PI);
  CHECK(std::abs(onset - expected) * 180.0 / M_PI < 0.5);
  // Before the onset it rolls: the contact point does not slip.
  const auto angle = run.values("plane.angle"), slip = run.values("plane.slip.x");
  for (std::size_t r = 0; r < angle.size(); ++r) {
    if (angle[r] < 0.98 * onset) REQUIRE(std::abs(slip[r]) < 1e-5);
  }
}

TEST_CASE("tilting planes with generated mu and tilt rates", "[contacts][tilt]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 2; ++i) {
    const double mu = 0.02 + 0.03 * uni(rng), rate = 0.1 + 0.3 * uni(rng),
                 radius = 0.05 + 0.1 * uni(rng);
    const double expected = std::atan(3.5 * mu);
    const std::string text =
        "[simulation]\ndt = 1e-4\noutput_rate = 2000.0\nduration = " + num(1.2 * expected / rate) +
        "\n[bodies.ball]\ntype = \"rigid_body\"\nshape = \"sphere\"\nmass = 2.0\nradius = " +
        num(radius) + "\nposition = [0.0, 0.0, " + num(radius) +
        "]\n[impedances.table_top]\ntype = \"kikuuwe_contact\"\n"
        "body = \"ball\"\ntilt = \"" +
        num(rate) +
        " * t\"\ntilt_axis = [0.0, 1.0, 0.0]\nstiffness = 1e7\n"
        "damping = 1000.0\nmu = " +
        num(mu) + "\nsettle = true\n";
    INFO(text);
    const auto run = run_text(text);
    REQUIRE_FALSE(run.result.instability);
    const double onset = slip_onset_angle(run, "table_top", mu);
    CHECK(std::abs(onset - expected) * 180.0 / M_PI < 0.5);
  }
}

TEST_CASE("a belt at rest and a zero tilt reproduce the fixed contact (sphere_roll)",
          "[contacts][belt]") {
  const auto fixed = run_scenario("sphere_roll");
  const auto belt = run_scenario("sphere_roll", {"impedances.ground.belt_speed=\"0*t\""});
  const auto tilt = run_scenario("sphere_roll", {"impedances.ground.tilt=0.0"});
  REQUIRE_FALSE(belt.result.instability);
  REQUIRE_FALSE(tilt.result.instability);
  for (const auto* moving : {&belt, &tilt}) {
    CHECK(moving->stick_time("ground") == Approx(fixed.stick_time("ground")).margin(1e-6));
    CHECK(moving->at("sphere.v.x", 2.0) == Approx(fixed.at("sphere.v.x", 2.0)).margin(1e-9));
    CHECK(moving->at("sphere.p.x", 2.0) == Approx(fixed.at("sphere.p.x", 2.0)).margin(1e-9));
  }
}
