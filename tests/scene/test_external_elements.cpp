// Elements supplied in code (scene/external_elements.hpp): a source law replacing a
// torque_source's or force_source's value, and an impedance for `type = "external"`, against
// the same scene written with an expression or a bundled element.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <random>

#include "components/impedance/spring_damper.hpp"
#include "core/simulation.hpp"
#include "scene/external_elements.hpp"
#include "scene/scene.hpp"

using namespace stiction;
using Catch::Matchers::Contains;

namespace {

scene::Scene from_text(const std::string& text,
                       std::shared_ptr<const scene::ExternalElements> externals = nullptr) {
  return scene::build_scene(toml::parse(text, std::string_view("x.toml")), "x.toml",
                            std::move(externals));
}

core::RunResult run(scene::Scene& s) { return core::simulate(*s.network, s.run); }

int column(const core::Trajectory& t, const std::string& name) {
  for (int c = 0; c < t.column_count(); ++c)
    if (t.columns()[c] == name) return c;
  FAIL("no column " << name);
  return -1;
}

// A one-link arm under gravity held by a PD controller with random gains; `torque` is the
// controller's value in the file.
std::string pd_arm(double kp, double kd, const std::string& torque) {
  return R"(
gravity = [0.0, 0.0, 0.0]
[simulation]
integrator = "rk4"
dt = 1e-4
duration = 0.5
output_rate = 1000.0
[bodies.arm]
type = "planar_arm"
axis = [0.0, -1.0, 0.0]
links = [{ length = 0.5, width = 0.02, mass = 1.0 }]
[impedances.spring]
type = "spring_damper"
body = "arm"
joint = 0
stiffness = 0.5
[impedances.controller]
type = "torque_source"
body = "arm"
joint = 0
)" + (torque.empty() ? std::string() : "torque = " + torque + "\n") +
         "# gains " + std::to_string(kp) + " " + std::to_string(kd) + "\n";
}

}  // namespace

TEST_CASE("external elements: a source law in code equals the same law as an expression") {
  std::mt19937 random(20);
  for (int trial = 0; trial < 3; ++trial) {
    const double kp = std::uniform_real_distribution<>(5.0, 40.0)(random);
    const double kd = std::uniform_real_distribution<>(0.1, 2.0)(random);
    char expression[200];
    std::snprintf(expression, sizeof expression, "\"%.17g*(1 - arm.theta.0) - %.17g*arm.omega.0\"",
                  kp, kd);
    scene::Scene with_expression = from_text(pd_arm(kp, kd, expression));

    auto externals = std::make_shared<scene::ExternalElements>();
    std::vector<std::string> seen;
    int builds = 0;
    externals->sources["controller"] = {
        std::nullopt, [&](const std::vector<std::string>& names, int count) -> scene::SourceLaw {
          seen = names;
          ++builds;
          REQUIRE(count == 1);
          return [kp, kd](double, const double* s, double* out) {
            out[0] = kp * (1 - s[0]) - kd * s[1];
          };
        }};
    scene::Scene with_law = from_text(pd_arm(kp, kd, "0.0"), externals);
    CHECK(builds == 1);
    // By default the law reads every signal of the admittances, in column order.
    REQUIRE(seen.size() >= 2);
    CHECK(seen[0] == "arm.theta.0");
    CHECK(seen[1] == "arm.omega.0");

    const core::RunResult a = run(with_expression), b = run(with_law);
    REQUIRE(a.trajectory.row_count() == b.trajectory.row_count());
    const int theta = column(a.trajectory, "arm.theta.0");
    const int tau = column(b.trajectory, "controller.tau");
    for (int r = 0; r < a.trajectory.row_count(); r += 50) {
      INFO("trial " << trial << " row " << r);
      CHECK(b.trajectory.at(r, theta) == Approx(a.trajectory.at(r, theta)).margin(1e-12));
      CHECK(b.trajectory.at(r, tau) == Approx(a.trajectory.at(r, tau)).margin(1e-9));
    }
    CHECK(std::abs(a.trajectory.at(a.trajectory.row_count() - 1, theta)) > 0.1);  // it moved
  }
}

TEST_CASE("external elements: a law reads the signals it names, other elements' outputs too") {
  auto externals = std::make_shared<scene::ExternalElements>();
  std::vector<std::string> seen;
  externals->sources["controller"] = {
      std::vector<std::string>{"spring.tau", "arm.omega.0"},
      [&](const std::vector<std::string>& names, int) -> scene::SourceLaw {
        seen = names;
        // Cancels the spring's torque: the arm then coasts at its initial rate.
        return [](double, const double* s, double* out) { out[0] = -s[0]; };
      }};
  // The placeholder may be left out when a law is supplied.
  std::string text = pd_arm(0, 0, "");
  text.replace(text.find("links ="), 0, "rates = [0.3]\n");
  scene::Scene s = from_text(text, externals);
  CHECK(seen == std::vector<std::string>{"spring.tau", "arm.omega.0"});
  const core::RunResult r = run(s);
  const int omega = column(r.trajectory, "arm.omega.0");
  CHECK(r.trajectory.at(r.trajectory.row_count() - 1, omega) == Approx(0.3).epsilon(1e-9));
}

TEST_CASE("external elements: a force law writes 3 values, from t alone") {
  auto externals = std::make_shared<scene::ExternalElements>();
  externals->sources["push"] = {std::vector<std::string>{},
                                [](const std::vector<std::string>&, int count) -> scene::SourceLaw {
                                  REQUIRE(count == 3);
                                  return [](double t, const double*, double* out) {
                                    out[0] = 2.0 * t;
                                    out[1] = 0.0;
                                    out[2] = 9.8 * 2.0;  // holds it against gravity
                                  };
                                }};
  scene::Scene s = from_text(R"(
[simulation]
duration = 1.0
[bodies.box]
type = "point_mass"
mass = 2.0
[impedances.push]
type = "force_source"
body = "box"
force = [0, 0, 0]
)",
                             externals);
  const core::RunResult r = run(s);
  const int last = r.trajectory.row_count() - 1;
  // m v' = 2 t: v(1) = 1 / m = 0.5 m/s, x(1) = 1 / (3 m) m.
  CHECK(r.trajectory.at(last, column(r.trajectory, "box.v.x")) == Approx(0.5).epsilon(1e-9));
  CHECK(r.trajectory.at(last, column(r.trajectory, "box.p.x")) == Approx(1.0 / 6.0).epsilon(1e-6));
  CHECK(std::abs(r.trajectory.at(last, column(r.trajectory, "box.v.z"))) < 1e-9);
}

TEST_CASE("external elements: mistakes are input errors that name the component") {
  auto unknown = std::make_shared<scene::ExternalElements>();
  unknown->sources["controller"] = {
      std::vector<std::string>{"arm.nothing"},
      [](const std::vector<std::string>&, int) { return scene::SourceLaw{}; }};
  CHECK_THROWS_WITH(from_text(pd_arm(1, 1, "0.0"), unknown), Contains("impedances.controller") &&
                                                                 Contains("'arm.nothing'") &&
                                                                 Contains("not a signal"));

  auto no_source = std::make_shared<scene::ExternalElements>();
  no_source->sources["motor"] = {
      std::nullopt, [](const std::vector<std::string>&, int) { return scene::SourceLaw{}; }};
  CHECK_THROWS_WITH(from_text(pd_arm(1, 1, "0.0"), no_source),
                    Contains("'motor'") && Contains("its sources: 'controller'"));

  auto spring_in_code = std::make_shared<scene::ExternalElements>();
  spring_in_code->impedances["spring"] = [](const std::string&) {
    return std::unique_ptr<core::Impedance>{};
  };
  CHECK_THROWS_WITH(from_text(pd_arm(1, 1, "0.0"), spring_in_code),
                    Contains("[impedances.spring]") && Contains("spring_damper"));
}

namespace {

std::string joint_scene(const std::string& type_and_keys) {
  return R"(
[simulation]
duration = 0.3
[bodies.arm]
type = "planar_arm"
links = [{ length = 0.4, mass = 0.5 }]
rates = [2.0]
[impedances.joint]
body = "arm"
joint = 0
)" + type_and_keys;
}

}  // namespace

TEST_CASE("external elements: an impedance in code, wired by its table, made per build") {
  std::mt19937 random(7);
  for (int trial = 0; trial < 3; ++trial) {
    components::SpringDamperParams p;
    p.stiffness = std::uniform_real_distribution<>(1.0, 50.0)(random);
    p.damping = std::uniform_real_distribution<>(0.0, 0.5)(random);
    p.dimension = 1;
    char keys[200];
    std::snprintf(keys, sizeof keys,
                  "type = \"spring_damper\"\nstiffness = %.17g\ndamping = %.17g\n", p.stiffness,
                  p.damping);
    scene::Scene bundled = from_text(joint_scene(keys));

    auto externals = std::make_shared<scene::ExternalElements>();
    int made = 0;
    externals->impedances["joint"] = [&](const std::string& name) {
      ++made;
      return std::make_unique<components::SpringDamper>(name, p);
    };
    scene::Scene first = from_text(joint_scene("type = \"external\"\n"), externals);
    scene::Scene second = from_text(joint_scene("type = \"external\"\n"), externals);
    CHECK(made == 2);
    const core::RunResult a = run(bundled), b = run(first);
    REQUIRE(a.trajectory.columns() == b.trajectory.columns());
    for (int r = 0; r < a.trajectory.row_count(); ++r)
      for (int c = 0; c < a.trajectory.column_count(); ++c)
        REQUIRE(a.trajectory.at(r, c) == b.trajectory.at(r, c));
  }
}

TEST_CASE("external elements: a missing factory or sizes that do not fit fail at the table") {
  CHECK_THROWS_WITH(from_text(joint_scene("type = \"external\"\n")),
                    Contains("x.toml:11:8:") && Contains("no element named 'joint'"));
  auto three_d = std::make_shared<scene::ExternalElements>();
  three_d->impedances["joint"] = [](const std::string& name) {
    components::SpringDamperParams p;  // 3-D: 6 inputs, 3 outputs
    return std::make_unique<components::SpringDamper>(name, p);
  };
  CHECK_THROWS_WITH(from_text(joint_scene("type = \"external\"\n"), three_d),
                    Contains("impedances.joint") && Contains("takes 6 inputs and gives 3") &&
                        Contains("input_size 2, output_size 1"));
  // The same element at a point of a body fits.
  scene::Scene point = from_text(R"(
[bodies.ball]
type = "point_mass"
mass = 1.0
position = [0.1, 0, 0]
[impedances.joint]
type = "external"
body = "ball"
point = [0, 0, 0]
)",
                                 three_d);
  CHECK(point.network->impedances().size() == 1);
}
