// Expressions of the state: signals named by their CSV columns, evaluated from the
// integrator's stage state; unknown names are errors at their column.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene/expression.hpp"
#include "sources_fixture.hpp"

using namespace stiction;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using scene::Expression;

TEST_CASE("state expression: uses the named signals, in the order it reports") {
  const std::vector<std::string> signals{"arm.theta.0", "arm.omega.0", "cart.p.x", "cart.v.x"};
  Expression e("-20*(arm.theta.0 - 1) - 2*arm.omega.0 + 0*t", signals);
  REQUIRE(e.used_signals() == std::vector<std::string>{"arm.omega.0", "arm.theta.0"});
  const double values[] = {3.0, 0.25};  // omega, theta
  CHECK(e.evaluate(0.0, values) == Approx(-20 * (0.25 - 1) - 2 * 3.0));
  // Numbers with exponents and dots are not taken for names.
  Expression f("1e-3*cart.p.x + .5 + 2.5e+1*t", signals);
  REQUIRE(f.used_signals() == std::vector<std::string>{"cart.p.x"});
  const double x = 4.0;
  CHECK(f.evaluate(2.0, &x) == Approx(4e-3 + 0.5 + 50.0));
}

TEST_CASE("state expression: an unknown signal is an error at its column, with suggestions") {
  toml::source_region where;
  where.begin = {5, 10};
  where.path = std::make_shared<const std::string>("s.toml");
  const std::vector<std::string> signals{"arm.theta.0", "arm.omega.0"};
  try {
    Expression e("2*arm.theta.0 - arm.omgea.0", where, "impedances.pd.torque", signals);
    FAIL("no error");
  } catch (const scene::InputError& e) {
    const std::string m = e.what();
    INFO(m);
    // The name starts at column 17 of the expression: 10 + 1 + 16 = 27.
    CHECK_THAT(m, StartsWith("s.toml:5:27: error: impedances.pd.torque"));
    CHECK_THAT(m, Contains("unknown name 'arm.omgea.0'"));
    CHECK_THAT(m, Contains("arm.theta.0, arm.omega.0"));
  }
  CHECK_THROWS_WITH(Expression("x + t"), Contains("unknown name 'x'"));
  CHECK_THROWS_AS(Expression("arm.theta.0 +", signals), scene::InputError);
}

TEST_CASE("state expression: in a scene, a bad signal name gives FILE:LINE:COL") {
  const std::string arm = testing::long_name("arm", 7);
  const std::string text =
      "gravity = [0.0, 0.0, 0.0]\n"
      "[bodies." +
      arm +
      "]\ntype = \"planar_arm\"\n"
      "links = [{length = 0.3, mass = 0.5}]\n"
      "[impedances.pd]\ntype = \"torque_source\"\nbody = \"" +
      arm +
      "\"\njoint = 0\n"
      "torque = \"-3*" +
      arm + ".theta.1\"\n";
  const std::string m = testing::load_error(text);
  INFO(m);
  // Line 9; the value's quote is at column 10, the name at column 4 of the expression.
  CHECK_THAT(m, StartsWith("gen.toml:9:14: error: impedances.pd.torque: invalid expression"));
  CHECK_THAT(m, Contains("unknown name '" + arm + ".theta.1'"));
  // A misspelt element signal too (elements' outputs are observable: test_impedance_signals).
  const std::string m2 = testing::load_error(
      "[bodies.b]\ntype = \"point_mass\"\nmass = 1\n"
      "[impedances.s]\ntype = \"spring_damper\"\nbody = \"b\"\n"
      "[impedances.push]\ntype = \"force_source\"\nbody = \"b\"\nforce = [\"s.f.q\", 0, 0]\n");
  INFO(m2);
  CHECK_THAT(m2, StartsWith("gen.toml:10:11: error: impedances.push.force[0]"));
  CHECK_THAT(m2, Contains("unknown name 's.f.q'"));
}

TEST_CASE("state expression: a feedback force sees the stage state (RK4 keeps its 4th order)") {
  // A point mass on a feedback spring f = -k x - c v, written as an expression of its own
  // state: the closed form is a damped oscillation. Were the force computed from the state
  // at the start of the step (not the stage's), RK4 would fall to first order: the error
  // would halve, not drop 16-fold, when the step halves.
  const double m = 0.7, k = 40.0, c = 0.9, x0 = 0.1;
  const double wn = std::sqrt(k / m), zeta = c / (2.0 * std::sqrt(k * m));
  const double wd = wn * std::sqrt(1.0 - zeta * zeta);
  auto exact = [&](double t) {
    return x0 * std::exp(-zeta * wn * t) *
           (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t));
  };
  auto error_at = [&](double dt) {
    const std::string body = testing::long_name("mass", 3);
    const std::string text =
        "gravity = [0.0, 0.0, 0.0]\n[simulation]\ndt = " + testing::num(dt) +
        "\nduration = 1.0\noutput_rate = 50.0\n"
        // The monitor integrates the sources' |power| every 8 steps; at these coarse steps
        // that undercounts the feedback spring's work, which starts the mass from rest.
        "energy_growth_limit = 10.0\n"
        "[bodies." +
        body + "]\ntype = \"point_mass\"\nmass = " + testing::num(m) + "\nposition = [" +
        testing::num(x0) +
        ", 0.0, 0.0]\n"
        "[impedances.feedback]\ntype = \"force_source\"\nbody = \"" +
        body +
        "\"\n"
        "force = [\"-" +
        testing::num(k) + "*" + body + ".p.x - " + testing::num(c) + "*" + body + ".v.x\", 0, 0]\n";
    const auto run = testing::run_text(text);
    if (run.result.instability) FAIL_CHECK(run.result.instability->reason);
    return run.worst_deviation(body + ".p.x", exact);
  };
  const double coarse = error_at(0.02), fine = error_at(0.01);
  INFO("error at dt 0.02: " << coarse << ", at dt 0.01: " << fine);
  CHECK(coarse < 1e-5);
  CHECK(coarse / fine > 12.0);  // 16 for a 4th-order method
}
