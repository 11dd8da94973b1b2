// Events kept up to a bound (issue 25): a scene that chatters keeps the first and the last
// events of each element and counts all of them. Generated chattering scenes: a mass on a belt
// whose speed is A sin(w t) with A w above the friction's acceleration mu g, so the mass
// sticks and slips twice per belt period (it rides the belt where |A w cos(w t)| < mu g and
// slides where the belt accelerates harder): 2 f T sticks in T seconds, the closed form the
// count of all events is checked against.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>

#include "child.hpp"

namespace fs = std::filesystem;
using namespace stiction::testing;

namespace {

struct Chatter {
  double mass, mu, frequency, ratio;  // ratio = A w / (mu g)
};

std::string chatter_scene(const Chatter& c, double duration) {
  const double g = 9.8, w = 2.0 * M_PI * c.frequency;
  const double amplitude = c.ratio * c.mu * g / w;
  std::ostringstream s;
  s.precision(17);
  s << "name = \"chatter\"\ngravity = [0.0, 0.0, -9.8]\n"
    << "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = " << duration << "\noutput_rate = 100.0\n"
    << "[bodies.mass]\ntype = \"point_mass\"\nmass = " << c.mass << "\nposition = [0.0, 0.0, 0.0]\n"
    << "[impedances.belt]\ntype = \"kikuuwe_contact\"\nbody = \"mass\"\nnormal = [0.0, 0.0, 1.0]\n"
    << "belt_speed = \"" << amplitude << " * sin(" << w << " * t)\"\nbelt_direction = [1.0, 0.0, 0.0]\n"
    << "stiffness = 1e6\ndamping = 2000.0\nmu = " << c.mu << "\nsettle = true\n";
  return s.str();
}

nlohmann::json run_summary(const fs::path& dir, const std::string& scene, std::string* console = nullptr) {
  std::ofstream(dir / "scene.toml") << scene;
  Child child({"run", "scene.toml", "--out", "out", "--no-plots", "--no-video"}, dir);
  const int code = child.wait(std::chrono::seconds(120));  // hang guard
  INFO(child.err());
  REQUIRE(code == 0);
  if (console != nullptr) *console = child.out();
  return nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
}

}  // namespace

TEST_CASE("a chattering element keeps its first and last events and counts all of them", "[bounded][events]") {
  std::mt19937 rng(2025);
  std::uniform_real_distribution<double> mass(0.5, 2.0), mu(0.2, 0.5), frequency(80.0, 120.0), ratio(1.6, 2.5);
  for (int k = 0; k < 3; ++k) {
    const Chatter c{mass(rng), mu(rng), frequency(rng), ratio(rng)};
    const double duration = 8.0;  // about 2 f T = 1300..1900 sticks, as many slips
    CAPTURE(k, c.mass, c.mu, c.frequency, c.ratio);
    const fs::path dir = scratch_dir("event_bound", "long" + std::to_string(k));
    std::string console;
    const nlohmann::json s = run_summary(dir, chatter_scene(c, duration), &console);
    const auto size = fs::file_size(dir / "out" / "summary.json");
    std::printf("chatter %d: summary %.0f kB\n", k, static_cast<double>(size) / 1e3);
    const nlohmann::json& belt = s["events"]["belt"];
    REQUIRE(belt.contains("events_dropped"));
    const auto kept = belt["events"].size();
    const auto total = belt["events_total"].get<std::size_t>();
    const auto dropped = belt["events_dropped"].get<std::size_t>();
    CHECK(kept <= 1000);
    CHECK(dropped > 0);
    CHECK(kept + dropped == total);
    CHECK(s["events_dropped"].get<std::size_t>() >= dropped);
    const auto& counts = belt["event_counts"];
    const auto sticks = counts["stick"].get<std::size_t>(), slips = counts["slip"].get<std::size_t>();
    CHECK(sticks + slips + counts["open"].get<std::size_t>() == total);
    // Alternating stick and slip: their counts differ by at most one.
    CHECK(std::abs(static_cast<double>(sticks) - static_cast<double>(slips)) <= 1.0);
    // The closed form: two sticks per belt period.
    CHECK(std::abs(static_cast<double>(sticks) - 2.0 * c.frequency * duration) <= 3.0);
    // The console counts all of them too.
    CHECK(console.find(std::to_string(sticks) + " sticks") != std::string::npos);
    // The summary stays small (every event kept: a few MB).
    CHECK(size < 1'000'000);

    // The intervals tile the run, the dropped stretch covering the gap between kept events.
    const auto& intervals = belt["intervals"];
    double end = 0.0;
    int gaps = 0;
    for (const auto& i : intervals) {
      CHECK(i["start"].get<double>() == end);
      end = i["end"].get<double>();
      gaps += i["kind"] == "dropped";
    }
    CHECK(gaps == 1);
    CHECK(end == Approx(duration));
    const double from = belt["dropped_from"].get<double>(), until = belt["dropped_until"].get<double>();
    CHECK(from < until);

    // The kept head is the run's first events: a run short enough to keep every event agrees
    // (the last two of the short run may still be settling at its end).
    const fs::path short_dir = scratch_dir("event_bound", "short" + std::to_string(k));
    const nlohmann::json sh = run_summary(short_dir, chatter_scene(c, 1.0));
    const auto& all = sh["events"]["belt"]["events"];
    REQUIRE(sh["events"]["belt"]["events_dropped"] == 0);
    REQUIRE(all.size() > 100);
    REQUIRE(all.size() < kept);
    for (std::size_t i = 0; i + 2 < all.size(); ++i) {
      CHECK(all[i]["kind"] == belt["events"][i]["kind"]);
      CHECK(all[i]["time"] == belt["events"][i]["time"]);
    }
    // The tail: the last events, after the dropped ones.
    CHECK(belt["events"].back()["time"].get<double>() > duration - 0.1);
    int after = 0;
    for (const auto& e : belt["events"]) after += e["time"].get<double>() > until;
    CHECK(after > 100);
  }
}
