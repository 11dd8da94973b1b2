// `stiction check` as a cheap CI gate: every value `run` rejects before simulating, check
// rejects with the same message and exit 2 (one case per table), and --json is parseable.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "ci_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

// a + b without GCC 12's -Wrestrict false positive on operator+ of literals and strings.
std::string cat(std::string a, const std::string& b) { return a.append(b); }

// Replaces the first occurrence of `from` (which must exist) in the scene text.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// The scene broken one way: check and run both exit 2 with the same located message.
void expect_same_rejection(const std::string& broken, const std::string& key,
                           const std::string& name) {
  const fs::path dir = scratch_dir("stiction_test_ci_check_", name);
  write_text(dir / "bad.toml", broken);
  const SplitOutcome check = run_split({"check", "bad.toml"}, dir);
  const SplitOutcome run = run_split({"run", "bad.toml", "--out", "out", "--quiet"}, dir);
  INFO("check: " << check.err << "\nrun: " << run.err);
  CHECK(check.code == 2);
  CHECK(run.code == 2);
  CHECK_THAT(check.err, Contains("bad.toml:"));
  CHECK_THAT(check.err, Contains(": error: "));
  CHECK_THAT(check.err, Contains(key));
  CHECK(check.err == run.err);
  CHECK_THAT(check.out, !Contains("ok"));
  // --json: the same error, located, on stdout.
  const SplitOutcome json = run_split({"check", "bad.toml", "--json"}, dir);
  CHECK(json.code == 2);
  const nlohmann::json j = nlohmann::json::parse(json.out);
  CHECK(j["ok"] == false);
  REQUIRE(j["errors"].size() == 1);
  CHECK(j["errors"][0]["file"].get<std::string>().find("bad.toml") != std::string::npos);
  CHECK(j["errors"][0]["line"].get<int>() > 0);
  CHECK_THAT(j["errors"][0]["message"].get<std::string>(), Contains(key));
}

}  // namespace

TEST_CASE("check: the generated scene passes check and --json describes it") {
  const fs::path dir = scratch_dir("stiction_test_ci_check_", "good");
  const std::string name =
      cat("a_ball_with_a_rather_long_name_for_a_scene_file_", std::string(40, 'x'));
  write_text(dir / "good.toml", ball_scene(name));
  const SplitOutcome text = run_split({"check", "good.toml"}, dir);
  INFO(text.out << text.err);
  REQUIRE(text.code == 0);
  CHECK_THAT(text.out, Contains(cat(name, ": ok")));
  // Each figure is named for what it is.
  CHECK_THAT(text.out, Contains("rk4               unstable above"));
  CHECK_THAT(text.out, Contains("alone, this undamped mode would make rk4 unstable above"));

  const SplitOutcome json = run_split({"check", "good.toml", "--json"}, dir);
  REQUIRE(json.code == 0);
  const nlohmann::json j = nlohmann::json::parse(json.out);
  CHECK(j["ok"] == true);
  CHECK(j["scene"] == name);
  CHECK(j["state_dim"] == 15);
  CHECK(j["layout"][0]["component"] == "ball");
  CHECK(j["render"]["size"] == nlohmann::json::array({320, 180}));
  CHECK(j["plots"] == nlohmann::json::array({"motion"}));
  for (const char* integrator : {"euler", "symplectic_euler", "heun", "rk4"}) {
    const nlohmann::json& l = j["step_limits"][integrator];
    INFO(integrator);
    REQUIRE(l.is_object());
    CHECK(l["unstable_above"].get<double>() > 0.0);
    // A chatter figure, when given, lies below the instability.
    if (!l["chatters_above"].is_null()) CHECK(l["chatters_above"] < l["unstable_above"]);
  }
  CHECK(j["step_limits"]["rk4"]["scene_dt_ok"] == true);
}

TEST_CASE("check: a bad [render] value is rejected as run rejects it") {
  expect_same_rejection(with(ball_scene("r"), "size = [320, 180]", "size = [1280, 721]"),
                        "render.size", "render");
}

TEST_CASE("check: a bad [camera] value is rejected as run rejects it") {
  expect_same_rejection(with(ball_scene("c"), "fov = 40", "fov = 40\nfollow = \"nobody\""),
                        "camera.follow", "camera");
}

TEST_CASE("check: a bad [overlay] value is rejected as run rejects it") {
  expect_same_rejection(
      with(ball_scene("o"), "signal = \"ground.slip\"", "signal = \"ground.slp\""),
      "overlay.signal", "overlay");
}

TEST_CASE("check: a bad [[plots]] value is rejected as run rejects it") {
  expect_same_rejection(with(ball_scene("p"), "\"ball.v.x\", \"ground", "\"ball.pz\", \"ground"),
                        "plots", "plots");
  expect_same_rejection(with(ball_scene("p2"), "#d55e00", "orange"), "colors", "plots_colour");
}

TEST_CASE("check: a bad [verify] value is rejected as run rejects it") {
  expect_same_rejection(ball_scene("v") + "\n[verify]\nat = [0.1, 7.0]\n", "verify.at",
                        "verify_at");
  expect_same_rejection(ball_scene("v2") + "\n[verify]\nmax_differing = 2.0\n",
                        "verify.max_differing", "verify_share");
  expect_same_rejection(ball_scene("v3") + "\n[verify]\npixel_tolerence = 3\n",
                        "verify.pixel_tolerence", "verify_unknown");
}
