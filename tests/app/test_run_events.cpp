// What `stiction run` says about events: on roll_to_slip (rolls, then slips at t* = 2.0 s)
// the report names the first slip and says the contact sticks from t = 0, and summary.json has
// the event model's fields (events, intervals with durations, first/last stick, first slip,
// stick_time kept for compatibility); the pushed boxes tip and slide at their closed forms, with
// body-level events printed and in summary.json `bodies`.
#include <catch2/catch.hpp>
#include <cmath>
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

namespace {
// The number printed after `prefix` in the output, or NaN when the prefix is missing.
double printed_after(const std::string& out, const std::string& prefix) {
  const auto at = out.find(prefix);
  return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + prefix.size()));
}
}  // namespace

TEST_CASE("run box_push_tip: the box tips at m g a / (h k), printed and in the summary") {
  // m = 1 kg, a = 0.1 m, h = 0.3 m, k = 2 N/s: t = 0.98 / 0.6 = 1.6333 s.
  const double expected = 1.0 * 9.8 * 0.1 / (0.3 * 2.0);
  const fs::path dir = scratch_dir("stiction_run_events_", "tip");
  const auto o =
      run_stiction({"run", "box_push_tip", "--no-video", "--no-plots", "--out", "o"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(printed_after(o.out, "box: starts sticking, tips at t = ") ==
        Approx(expected).margin(2e-4));
  // The back corners lift off without slipping first: stuck throughout the time they touch.
  CHECK(o.out.find("floor.0: sticks throughout (starts stick; 0 sticks, 0 slips, 1 lift-off)") !=
        std::string::npos);
  CHECK(o.out.find("floor.4: never touches") != std::string::npos);
  std::ifstream in(dir / "o" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const auto& box = s["bodies"]["box"];
  CHECK(box["initial"] == "stick");
  CHECK(box["points"].size() == 8);
  REQUIRE(box["events"].size() == 1);
  CHECK(box["events"][0]["kind"] == "tip");
  CHECK(box["events"][0]["time"].get<double>() == Approx(expected).margin(2e-4));
  REQUIRE(box["intervals"].size() == 2);
  CHECK(box["intervals"][1]["kind"] == "tip");
  CHECK(box["intervals"][1]["end"].get<double>() == Approx(2.0));
  // The per-element events keep their contract.
  CHECK(s["events"]["floor.0"]["events"][0]["kind"] == "open");
  fs::remove_all(dir);
}

TEST_CASE("run box_push_slide: the box slides at mu m g / k, its creeping corners are stuck") {
  // mu = 0.5, m = 1 kg, k = 2 N/s: t = 2.45 s. The back corners reach their own friction
  // limit from 1.96 s on and creep at about 1 um/s, below the 1 mm/s threshold: stuck.
  const double expected = 0.5 * 1.0 * 9.8 / 2.0;
  const fs::path dir = scratch_dir("stiction_run_events_", "slide");
  const auto o =
      run_stiction({"run", "box_push_slide", "--no-video", "--no-plots", "--out", "o"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(printed_after(o.out, "box: starts sticking, slides at t = ") ==
        Approx(expected).margin(2e-4));
  for (const char* corner : {"floor.0", "floor.1", "floor.2", "floor.3"}) {
    CHECK(printed_after(o.out, std::string(corner) + ": sticks from t = 0, first slip at t = ") ==
          Approx(expected).margin(2e-4));
  }
  std::ifstream in(dir / "o" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const auto& box = s["bodies"]["box"];
  REQUIRE(box["events"].size() == 1);
  CHECK(box["events"][0]["kind"] == "slide");
  CHECK(box["events"][0]["time"].get<double>() == Approx(expected).margin(2e-4));
  CHECK(s["events"]["floor.0"]["first_slip"].get<double>() == Approx(expected).margin(2e-4));
  fs::remove_all(dir);
}

TEST_CASE("run: a contact sliding the whole run slides throughout, times with 7 digits") {
  // A box launched at 1 m/s on a floor with mu = 0.2 stops at 1 / (0.2 g) = 0.5102 s; run
  // for 0.4 s it slides throughout, run for 0.8 s it sticks at that time.
  const fs::path dir = scratch_dir("stiction_run_events_", "launched");
  {
    std::ofstream scene(dir / "launched.toml");
    scene << "[simulation]\nduration = 0.4\n[bodies.crate]\ntype = \"rigid_body\"\nmass = 1.0\n"
             "shape = \"box\"\nsize = [0.2, 0.2, 0.1]\nposition = [0.0, 0.0, 0.05]\n"
             "velocity = [1.0, 0.0, 0.0]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\n"
             "body = \"crate\"\nstiffness = 1e6\ndamping = 1000.0\nmu = 0.2\nsettle = true\n";
  }
  auto o = run_stiction({"run", "launched.toml", "--no-video", "--no-plots", "--out", "a"}, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK(o.out.find("floor.0: slides throughout (starts slip; 0 sticks, 0 slips)") !=
        std::string::npos);
  CHECK(o.out.find("crate: slides throughout") != std::string::npos);
  o = run_stiction(
      {"run", "launched.toml", "--duration", "0.8", "--no-video", "--no-plots", "--out", "b"}, dir);
  REQUIRE(o.code == 0);
  const std::string line = "crate: starts sliding, sticks at t = ";
  const auto at = o.out.find(line);
  REQUIRE(at != std::string::npos);
  const std::string time =
      o.out.substr(at + line.size(), o.out.find(' ', at + line.size()) - (at + line.size()));
  CHECK(std::stod(time) == Approx(1.0 / (0.2 * 9.8)).epsilon(1e-3));
  CHECK(time.size() == 9);  // "0.5102041": 7 significant digits
  fs::remove_all(dir);
}
