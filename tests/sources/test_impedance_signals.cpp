// Expressions reading the outputs of impedances by their CSV names (a contact's friction
// force, a spring's force, a joint friction's torque), evaluated at every integrator stage
// from the stage state; algebraic loops between sources are rejected at the name.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>

#include "sources_fixture.hpp"

using namespace stiction;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using testing::num;

namespace {

// A point mass on a settled Kikuuwe floor contact, sliding along +x at v0 (gravity -9.8 z).
std::string sliding_block(const std::string& block, double m, double mu, double v0,
                          double duration) {
  const double k = 1e5, b = 2.0 * std::sqrt(k * m);
  return "[simulation]\ndt = 1e-4\noutput_rate = 1000.0\nduration = " + num(duration) +
         "\n"
         "[bodies." +
         block + "]\ntype = \"point_mass\"\nmass = " + num(m) + "\nvelocity = [" + num(v0) +
         ", 0.0, 0.0]\n"
         "[impedances.floor_contact]\ntype = \"kikuuwe_contact\"\nbody = \"" +
         block + "\"\nstiffness = " + num(k) + "\ndamping = " + num(b) + "\nmu = " + num(mu) +
         "\nsettle = true\n";
}

}  // namespace

TEST_CASE("impedance signals: a sliding block's friction read by name is exactly mu m g") {
  std::mt19937 rng(101);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double m = 0.3 + 2.0 * u(rng), mu = 0.1 + 0.5 * u(rng), v0 = 0.5 + u(rng);
    const double mp = 0.5 + u(rng), g = 9.8;
    const std::string block = testing::long_name("block", trial);
    // A free probe mass far away, pushed by the contact's force as read by name; it is
    // defined before the contact is, in the file. The probe floats: its source carries
    // m_p g upward too.
    std::string text = sliding_block(block, m, mu, v0, 1.5 * v0 / (mu * g));
    text += "[bodies.probe]\ntype = \"point_mass\"\nmass = " + num(mp) +
            "\nposition = [0.0, 5.0, 3.0]\n"
            "[impedances.reader]\ntype = \"force_source\"\nbody = \"probe\"\n"
            "force = [\"floor_contact.f.x\", \"floor_contact.f.y\", \"floor_contact.f.z - " +
            num(m * g) + " + " + num(mp * g) + "\"]\n";
    const auto run = testing::run_text(text);
    REQUIRE_FALSE(run.result.instability);
    const auto t = run.times();
    const auto v = run.values(block + ".v.x"), fx = run.values("reader.f.x"),
               cx = run.values("floor_contact.f.x"), nz = run.values("floor_contact.n_force"),
               pv = run.values("probe.v.x"), pz = run.values("probe.p.z");
    const double t_stop = v0 / (mu * g);
    int sliding = 0;
    double worst_f = 0.0, worst_v = 0.0, worst_n = 0.0;
    for (std::size_t r = 1; r < t.size(); ++r) {
      CHECK(fx[r] == cx[r]);  // the same evaluation as the contact's own column
      if (t[r] > 0.95 * t_stop) continue;
      ++sliding;
      worst_n = std::max(worst_n, std::abs(nz[r] / (m * g) - 1.0));
      worst_f = std::max(worst_f, std::abs(fx[r] / (-mu * m * g) - 1.0));
      // The probe integrates the value read at every stage: v = -mu m g t / m_p.
      worst_v = std::max(worst_v, std::abs(pv[r] - (-mu * m * g * t[r] / mp)));
    }
    INFO("m " << m << " mu " << mu << " v0 " << v0 << ": friction read " << worst_f
              << " (relative), normal " << worst_n << ", probe speed " << worst_v);
    std::printf(
        "impedance signals: sliding block m %.3f mu %.3f: friction read vs -mu m g %.1e "
        "(relative), probe speed vs -mu m g t / m_p %.1e m/s\n",
        m, mu, worst_f, worst_v);
    CHECK(sliding > 20);
    CHECK(worst_n < 1e-9);
    CHECK(worst_f < 1e-9);
    CHECK(worst_v < 1e-9);
    CHECK(std::abs(pz.back() - 3.0) < 1e-6);  // weight and normal force cancel on the probe
    // After the stop, static friction holds the block, below the limit.
    CHECK(std::abs(v.back()) < 1e-4);
    CHECK(std::abs(fx.back()) < mu * m * g);
  }
}

TEST_CASE("impedance signals: a force equal to minus the friction keeps a block sliding") {
  std::mt19937 rng(202);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2; ++trial) {
    const double m = 0.3 + 2.0 * u(rng), mu = 0.2 + 0.5 * u(rng), v0 = 0.3 + u(rng);
    const std::string block = testing::long_name("slider", trial);
    // Unopposed, it would stop at v0 / (mu g); the source cancels the friction at every stage.
    const double duration = 2.0 * v0 / (mu * 9.8);
    std::string text = "[impedances.cancel]\ntype = \"force_source\"\nbody = \"" + block +
                       "\"\nforce = [\"-floor_contact.f.x\", \"-floor_contact.f.y\", 0]\n";
    text = sliding_block(block, m, mu, v0, duration) + text;
    const auto run = testing::run_text(text);
    REQUIRE_FALSE(run.result.instability);
    const auto t = run.times();
    const auto v = run.values(block + ".v.x"), x = run.values(block + ".p.x"),
               f = run.values("cancel.f.x");
    double worst = 0.0;
    for (std::size_t r = 0; r < t.size(); ++r) {
      worst = std::max({worst, std::abs(v[r] - v0), std::abs(x[r] - v0 * t[r])});
    }
    std::printf(
        "impedance signals: friction cancelled (m %.3f, mu %.3f, v0 %.3f): |v - v0|, "
        "|x - v0 t| at most %.1e\n",
        m, mu, v0, worst);
    CHECK(worst < 1e-9);
    CHECK(f.back() == Approx(mu * m * 9.8).epsilon(1e-9));
  }
}

TEST_CASE("impedance signals: a force proportional to a spring's force (RK4 keeps its order)") {
  // A mass on a spring k, pushed by alpha times the spring's force: it oscillates at
  // w = sqrt((1 + alpha) k / m). The spring's force is evaluated at each stage from the stage
  // state; read from the last step instead, RK4 would fall to first order.
  const double m = 0.8, k = 30.0, alpha = 0.6, x0 = 0.05;
  const double w = std::sqrt((1.0 + alpha) * k / m);
  auto error_at = [&](double dt) {
    const std::string body = testing::long_name("mass", 5);
    const std::string text =
        "gravity = [0.0, 0.0, 0.0]\n[simulation]\ndt = " + num(dt) +
        "\nduration = 1.0\noutput_rate = 50.0\nenergy_growth_limit = 10.0\n"
        "[impedances.amplifier]\ntype = \"force_source\"\nbody = \"" +
        body + "\"\nforce = [\"" + num(alpha) + "*coil.f.x\", \"" + num(alpha) +
        "*coil.f.y\", 0]\n"
        "[bodies." +
        body + "]\ntype = \"point_mass\"\nmass = " + num(m) + "\nposition = [" + num(x0) +
        ", 0.0, 0.0]\n"
        "[impedances.coil]\ntype = \"spring_damper\"\nbody = \"" +
        body + "\"\nstiffness = " + num(k) + "\n";
    const auto run = testing::run_text(text);
    if (run.result.instability) FAIL_CHECK(run.result.instability->reason);
    return run.worst_deviation(body + ".p.x", [&](double t) { return x0 * std::cos(w * t); });
  };
  const double coarse = error_at(0.02), fine = error_at(0.01);
  std::printf(
      "impedance signals: force alpha * spring force: error %.2e at dt 0.02, %.2e at "
      "dt 0.01 (ratio %.1f)\n",
      coarse, fine, coarse / fine);
  CHECK(coarse < 1e-5);
  CHECK(coarse / fine > 12.0);  // 16 for a 4th-order method
}

TEST_CASE("impedance signals: a torque cancelling a joint friction read by name") {
  // A one-link arm turning in the horizontal plane against Kikuuwe joint friction F; a
  // torque source equal to minus the friction's torque keeps its rate. Sources chain: a
  // second source reads the first one's output.
  const double omega0 = 1.7, F = 0.4;
  const std::string arm = testing::long_name("arm", 9);
  const std::string text = "[simulation]\ndt = 1e-3\nduration = 2.0\n[bodies." + arm +
                           "]\ntype = \"planar_arm\"\nlinks = [{length = 0.4, mass = 0.6}]\n"
                           "rates = [" +
                           num(omega0) +
                           "]\n"
                           "[impedances.echo]\ntype = \"force_source\"\nbody = \"probe\"\n"
                           "force = [\"2*motor.tau\", 0, 9.8]\n"
                           "[impedances.motor]\ntype = \"torque_source\"\nbody = \"" +
                           arm +
                           "\"\njoint = 0\ntorque = \"-bearing.tau\"\n"
                           "[impedances.bearing]\ntype = \"kikuuwe_friction\"\nbody = \"" +
                           arm + "\"\njoint = 0\nforce_limit = " + num(F) +
                           "\n"
                           "[bodies.probe]\ntype = \"point_mass\"\nmass = 1.0\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const auto t = run.times();
  const auto omega = run.values(arm + ".omega.0"), tau = run.values("motor.tau"),
             friction = run.values("bearing.tau"), echo = run.values("echo.f.x"),
             probe = run.values("probe.v.x");
  for (std::size_t r = 0; r < t.size(); ++r) {
    CHECK(omega[r] == Approx(omega0).epsilon(1e-12));
    CHECK(tau[r] == -friction[r]);
    CHECK(echo[r] == 2.0 * tau[r]);
  }
  CHECK(tau.back() == Approx(F).epsilon(1e-9));
  CHECK(probe.back() == Approx(2.0 * F * t.back()).epsilon(1e-9));
  // The columns keep the file's order, though `echo` was built after what it reads.
  const auto columns = run.scene.network->signal_columns();
  const auto at = [&](const std::string& c) {
    return std::find(columns.begin(), columns.end(), c);
  };
  CHECK(at("echo.f.x") < at("motor.tau"));
  CHECK(at("motor.tau") < at("bearing.tau"));
}

TEST_CASE("impedance signals: algebraic loops and unknown names are located errors") {
  const std::string ball = "[bodies.ball]\ntype = \"point_mass\"\nmass = 1\n";  // lines 1-3
  auto source = [](const std::string& name, const std::string& fx) {
    return "[impedances." + name + "]\ntype = \"force_source\"\nbody = \"ball\"\nforce = [\"" + fx +
           "\", 0, 0]\n";  // 4 lines, `force` on the 4th
  };
  // A source reading its own value: line 7, the name at column 4 of the expression.
  std::string m = testing::load_error(ball + source("self", "1 + self.f.x"));
  INFO(m);
  CHECK_THAT(m, StartsWith("gen.toml:7:15: error: impedances.self.force[0]: 'self.f.x'"));
  CHECK_THAT(m, Contains("algebraic loop"));
  // Through another source, even one written later: reported where the loop closes.
  m = testing::load_error(ball + source("first", "2*second.f.x") + source("second", "first.f.x"));
  INFO(m);
  CHECK_THAT(m, StartsWith("gen.toml:11:11: error: impedances.second.force[0]: 'first.f.x'"));
  CHECK_THAT(m, Contains("algebraic loop (first -> second -> first)"));
  // Three sources in a ring, with long names.
  const std::string a = testing::long_name("a", 1), b = testing::long_name("b", 2),
                    c = testing::long_name("c", 3);
  m = testing::load_error(ball + source(a, b + ".f.x") + source(b, c + ".f.x") +
                          source(c, "t + " + a + ".f.x"));
  INFO(m);
  CHECK_THAT(m, StartsWith("gen.toml:15:15: error: impedances." + c + ".force[0]"));
  CHECK_THAT(m, Contains(a + " -> " + b + " -> " + c + " -> " + a));
  // A chain without a loop is fine, and a source may read a spring's force.
  CHECK(testing::load_error(ball + source("up", "down.f.x") + source("down", "2*t")) == "");
  // Unknown names stay errors at their column, with the component's signals suggested.
  m = testing::load_error(ball + "[impedances.s]\ntype = \"spring_damper\"\nbody = \"ball\"\n" +
                          source("push", "s.f.w"));
  INFO(m);
  CHECK_THAT(m, StartsWith("gen.toml:10:11: error: impedances.push.force[0]"));
  CHECK_THAT(m, Contains("unknown name 's.f.w'"));
  CHECK_THAT(m, Contains("s.f.x, s.f.y, s.f.z"));
}

TEST_CASE("impedance signals: a box's corner contacts read by their element names") {
  // A box sliding on its face has one contact element per corner (floor.0 .. floor.7); a
  // probe's force is the sum of their friction forces, mu times the box's weight.
  const double m = 1.3, mu = 0.35, v0 = 0.8, g = 9.8;
  const std::string box = testing::long_name("box", 4);
  std::string sum;
  for (int i = 0; i < 8; ++i) sum += (i ? " + floor." : "floor.") + std::to_string(i) + ".f.x";
  const std::string text =
      "[simulation]\ndt = 1e-4\noutput_rate = 1000.0\nduration = 0.15\n[bodies." + box +
      "]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = " + num(m) +
      "\nsize = [0.2, 0.15, 0.1]\nposition = [0.0, 0.0, 0.05]\nvelocity = [" + num(v0) +
      ", 0.0, 0.0]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"" + box +
      "\"\nstiffness = 1e6\ndamping = 600.0\nmu = " + num(mu) +
      "\nsettle = true\n[bodies.probe]\ntype = \"point_mass\"\nmass = 1.0\n"
      "[impedances.reader]\ntype = \"force_source\"\nbody = \"probe\"\nforce = [\"" +
      sum + "\", 0, 9.8]\n";
  const auto run = testing::run_text(text);
  REQUIRE_FALSE(run.result.instability);
  const auto t = run.times();
  const auto read = run.values("reader.f.x");
  double worst = 0.0, mean = 0.0;
  for (std::size_t r = 0; r < t.size(); ++r) {
    double columns = 0.0, normals = 0.0;
    for (int i = 0; i < 8; ++i) {
      columns += run.values("floor." + std::to_string(i) + ".f.x")[r];
      normals += run.values("floor." + std::to_string(i) + ".n_force")[r];
    }
    worst = std::max(worst, std::abs(read[r] - columns));
    CHECK(read[r] == Approx(-mu * normals).epsilon(1e-12));  // every corner slides
    mean += read[r] / static_cast<double>(t.size());
  }
  std::printf(
      "impedance signals: box corners: read vs sum of columns %.1e N, mean %.6f N "
      "(-mu m g = %.6f N)\n",
      worst, mean, -mu * m * g);
  CHECK(worst < 1e-12);
  CHECK(mean == Approx(-mu * m * g).epsilon(1e-2));
}
