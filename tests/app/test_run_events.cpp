// What `stiction run` says about events: on roll_to_slip (rolls, then slips at t* = 2.0 s)
// the report names the first slip and says the contact sticks from t = 0, and summary.json has
// the event model's fields (events, intervals with durations, first/last stick, first slip,
// stick_time kept for compatibility).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "run_stiction.hpp"

namespace fs = std::filesystem;
using stiction::testing::run_stiction;
using stiction::testing::scratch_dir;

TEST_CASE("run roll_to_slip: first slip printed and in the summary, no stick") {
  const fs::path dir = scratch_dir("stiction_run_events_", "roll");
  const auto o =
      run_stiction({"run", "roll_to_slip", "--no-video", "--no-plots", "--out", "o"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  const std::string printed = "ground: sticks from t = 0, first slip at t = ";
  const auto at = o.out.find(printed);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(o.out.substr(at + printed.size())) == Approx(2.0).epsilon(5e-3));
  std::ifstream in(dir / "o" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const auto& g = s["events"]["ground"];
  CHECK(g["initial"] == "stick");
  CHECK(g["stick_time"].is_null());
  CHECK(g["first_stick"].is_null());
  CHECK(g["last_stick"].is_null());
  REQUIRE(g["first_slip"].is_number());
  CHECK(g["first_slip"].get<double>() == Approx(2.0).epsilon(5e-3));
  REQUIRE(g["events"].size() == 1);
  CHECK(g["events"][0]["kind"] == "slip");
  REQUIRE(g["intervals"].size() == 2);
  CHECK(g["intervals"][0]["kind"] == "stick");
  CHECK(g["intervals"][0]["duration"].get<double>() == Approx(g["first_slip"].get<double>()));
  CHECK(g["intervals"][1]["kind"] == "slip");
  CHECK(g["intervals"][1]["end"].get<double>() == Approx(3.0));
  fs::remove_all(dir);
}

TEST_CASE("run sphere_roll: touch-downs, a stick, both printed") {
  const fs::path dir = scratch_dir("stiction_run_events_", "sphere");
  const auto o =
      run_stiction({"run", "sphere_roll", "--no-video", "--no-plots", "--out", "o"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(o.out.find("ground: first stick at t = 0.58") != std::string::npos);
  CHECK(o.out.find("first slip at t = ") != std::string::npos);
  CHECK(o.out.find("starts open") != std::string::npos);
  std::ifstream in(dir / "o" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const auto& g = s["events"]["ground"];
  CHECK(g["stick_time"] == g["first_stick"]);
  REQUIRE(g["events"].size() >= 2);
  CHECK(g["events"][0]["touch_down"] == true);  // it starts in the air
  fs::remove_all(dir);
}
