// Plausibility warnings (scene/plausibility.hpp): each fires on a generated scene with the
// mistake, at the mistake's line and key; none fires on the same scenes without it nor on a
// bundled scene; `run` puts them in summary.json and on stderr (not with --quiet), `check`
// in its text and --json output.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../app/run_stiction.hpp"
#include "scene/scene.hpp"

using namespace stiction;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << std::scientific << x;
  return out.str();
}

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << std::scientific << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
  return out.str();
}

// A scene file as lines, so that a test knows on which line its mistake is.
struct Lines {
  std::vector<std::string> lines;
  int add(const std::string& line) {
    lines.push_back(line);
    return static_cast<int>(lines.size());  // 1-based line number
  }
  std::string text() const {
    std::string t;
    for (const auto& l : lines) t += l + "\n";
    return t;
  }
};

scene::Scene from_text(const std::string& text) {
  return scene::build_scene(toml::parse(std::string_view(text), std::string_view("gen.toml")),
                            "gen.toml");
}

// What a generated scene may get wrong, one at a time.
enum class Mistake {
  none,
  gravity_up,
  gravity_units,
  mu,
  tilt,
  radius,
  settle_above,
  dt,
  rows,
  threshold,
  sunk
};

struct Generated {
  std::string text;
  int line = 0;     // the mistake's line
  std::string key;  // the key its warning must name
};

// A sphere resting (settled) on a plane of random orientation and offset, gravity against
// its normal, launched along the plane; with one mistake.
Generated ball_on_plane(std::mt19937& rng, Mistake mistake) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  Eigen::Vector3d n(uniform(-1, 1), uniform(-1, 1), uniform(0.3, 1));
  n.normalize();
  Eigen::Vector3d t = n.cross(Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
  t.normalize();
  const double g = uniform(3.0, 12.0), offset = uniform(-1.0, 1.0);
  const double m = uniform(0.5, 8.0), density = uniform(200.0, 8000.0);
  const double radius =
      mistake == Mistake::radius ? uniform(5.0, 15.0) : std::cbrt(3 * m / (4 * 3.14159 * density));
  const double v0 = uniform(0.5, 5.0);
  Lines l;
  Generated out;
  auto mark = [&](Mistake which, const std::string& key, int line) {
    if (mistake == which) {
      out.line = line;
      out.key = key;
    }
  };
  l.add("name = \"gen\"");
  // Up, or in mm/s^2.
  const double gravity = mistake == Mistake::gravity_up      ? g
                         : mistake == Mistake::gravity_units ? -1000.0 * g
                                                             : -g;
  const int gravity_line = l.add("gravity = " + vec(gravity * n));
  mark(Mistake::gravity_up, "gravity", gravity_line);
  mark(Mistake::gravity_units, "gravity", gravity_line);
  l.add("[simulation]");
  mark(Mistake::dt, "simulation.dt", l.add(mistake == Mistake::dt ? "dt = 0.5" : "dt = 1e-4"));
  l.add("duration = 0.2");
  mark(Mistake::rows, "simulation.output_rate",
       l.add(mistake == Mistake::rows ? "output_rate = 20.0" : "output_rate = 1000.0"));
  l.add("[bodies.ball]");
  l.add("type = \"rigid_body\"");
  l.add("mass = " + number(m));
  l.add("shape = \"sphere\"");
  mark(Mistake::radius, "bodies.ball.radius", l.add("radius = " + number(radius)));
  const double lift = mistake == Mistake::settle_above ? uniform(0.01, 1.0)
                     : mistake == Mistake::sunk       ? -uniform(0.03, 0.5) * radius
                                                      : 0.0;
  mark(Mistake::sunk, "bodies.ball.position",
       l.add("position = " + vec((offset + radius + lift) * n)));
  l.add("velocity = " + vec(v0 * t));
  l.add("[impedances.floor]");
  l.add("type = \"kikuuwe_contact\"");
  l.add("body = \"ball\"");
  l.add("normal = " + vec(n));
  l.add("offset = " + number(offset));
  mark(Mistake::mu, "impedances.floor.mu",
       l.add("mu = " + number(mistake == Mistake::mu ? uniform(2.5, 50.0) : uniform(0.05, 1.0))));
  // Sunk: the user did not ask for rest (settle would place it on the surface).
  if (mistake != Mistake::sunk) {
    mark(Mistake::settle_above, "impedances.floor.settle", l.add("settle = true"));
  }
  if (mistake == Mistake::tilt) {
    mark(mistake, "impedances.floor.tilt", l.add("tilt = " + number(uniform(5.0, 45.0))));
  }
  mark(Mistake::threshold, "impedances.floor.stick_threshold",
       l.add("stick_threshold = " +
             number(mistake == Mistake::threshold ? uniform(1.5, 3.0) * v0 : 1e-3)));
  out.text = l.text();
  return out;
}

// A one-link arm whose initial angle is in degrees.
Generated arm_in_degrees(std::mt19937& rng, bool mistake) {
  const double degrees = std::uniform_real_distribution<double>(10.0, 170.0)(rng);
  Lines l;
  l.add("gravity = [0.0, 0.0, 0.0]");
  l.add("[bodies.arm]");
  l.add("type = \"planar_arm\"");
  l.add("links = [{ length = 0.3, mass = 0.5, width = 0.03 }]");
  const int line = l.add("angles = [" + number(mistake ? degrees : degrees * 3.14159 / 180) + "]");
  return {l.text(), mistake ? line : 0, mistake ? "bodies.arm.angles" : ""};
}

void check_generated(const Generated& g) {
  INFO("scene:\n" << g.text);
  const scene::Scene s = from_text(g.text);
  std::string all;
  for (const auto& w : s.warnings) all += scene::format_warning(w) + "\n";
  INFO("warnings:\n" << all);
  if (g.key.empty()) {
    CHECK(s.warnings.empty());
    return;
  }
  bool found = false;
  for (const scene::Warning& w : s.warnings) {
    if (w.key != g.key) continue;
    found = true;
    CHECK(w.file == "gen.toml");
    CHECK(w.line == g.line);
    CHECK(w.column >= 1);
    CHECK_THAT(w.text, Catch::Matchers::StartsWith(g.key + ": "));
    CHECK_THAT(scene::format_warning(w),
               Catch::Matchers::StartsWith("gen.toml:" + std::to_string(g.line) + ":"));
  }
  CHECK(found);
}

fs::path scratch(const std::string& name) {
  return stiction::testing::scratch_dir("stiction_test_plausibility_", name);
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("plausibility: each mistake warns at its line and key, none without it") {
  std::mt19937 rng(4242);
  for (int i = 0; i < 4; ++i) {
    for (const Mistake m :
         {Mistake::none, Mistake::gravity_up, Mistake::gravity_units, Mistake::mu, Mistake::tilt,
          Mistake::radius, Mistake::settle_above, Mistake::rows, Mistake::threshold, Mistake::sunk}) {
      // Mistake::dt (dt > duration) is an error since issue 25, no longer a warning
      // (tests/reliability/test_input_values.cpp).
      check_generated(ball_on_plane(rng, m));
    }
    check_generated(arm_in_degrees(rng, true));
    check_generated(arm_in_degrees(rng, false));
  }
}

// Issue 39: bodies that start inside a surface or inside each other were launched at
// hundreds of m/s with status ok. A box of random orientation sunk by a random fraction of its
// size, and two spheres overlapping: warned at the body's position beyond 1% of its size, not
// below; settle = true places a sunk sphere on its surface instead (no warning).
TEST_CASE("plausibility: a body that starts inside a surface or another body is warned") {
  std::mt19937 rng(39);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  for (int i = 0; i < 6; ++i) {
    const bool deep = i % 2 == 0;
    // A box resting on one corner (random orientation), the corner sunk.
    const Eigen::Vector3d size(uniform(0.05, 0.5), uniform(0.05, 0.5), uniform(0.05, 0.5));
    const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
    const Eigen::Vector3d half = 0.5 * size;
    double lowest = 0.0;  // the lowest corner's height below the centre
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1 ? 1 : -1) * half.x(), (c & 2 ? 1 : -1) * half.y(),
                                   (c & 4 ? 1 : -1) * half.z());
      lowest = std::max(lowest, -(q * corner).z());
    }
    const double sink = (deep ? uniform(0.03, 0.5) : uniform(0.0, 0.005)) * half.minCoeff();
    Lines l;
    l.add("[bodies.crate]");
    l.add("type = \"rigid_body\"");
    l.add("shape = \"box\"");
    l.add("mass = " + number(uniform(1.0, 20.0)));
    l.add("size = " + vec(size));
    const int line = l.add("position = " + vec(Eigen::Vector3d(0.0, 0.0, lowest - sink)));
    l.add("orientation = [" + number(q.w()) + ", " + number(q.x()) + ", " + number(q.y()) +
          ", " + number(q.z()) + "]");
    l.add("[impedances.floor]");
    l.add("type = \"kikuuwe_contact\"");
    l.add("body = \"crate\"");
    l.add("stiffness = " + number(uniform(1e4, 1e7)));
    check_generated({l.text(), deep ? line : 0, deep ? "bodies.crate.position" : ""});

    // Two spheres overlapping by a fraction of the smaller one, no gravity.
    const double r1 = uniform(0.05, 0.3), r2 = uniform(0.05, 0.3);
    const double overlap = (deep ? uniform(0.03, 0.5) : uniform(0.0, 0.005)) * std::min(r1, r2);
    Eigen::Vector3d axis(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    axis.normalize();
    Lines p;
    p.add("gravity = [0.0, 0.0, 0.0]");
    p.add("[bodies.a]");
    p.add("type = \"rigid_body\"");
    p.add("shape = \"sphere\"");
    p.add("mass = " + number(4.0 / 3.0 * 3.14159 * r1 * r1 * r1 * 2000.0));
    p.add("radius = " + number(r1));
    const int at = p.add("position = [0.0, 0.0, 0.0]");
    p.add("[bodies.b]");
    p.add("type = \"rigid_body\"");
    p.add("shape = \"sphere\"");
    p.add("mass = " + number(4.0 / 3.0 * 3.14159 * r2 * r2 * r2 * 2000.0));
    p.add("radius = " + number(r2));
    p.add("position = " + vec((r1 + r2 - overlap) * axis));
    p.add("[impedances.touch]");
    p.add("type = \"kikuuwe_contact\"");
    p.add("body = \"a\"");
    p.add("other = \"b\"");
    check_generated({p.text(), deep ? at : 0, deep ? "bodies.a.position" : ""});
  }
  // A sunk sphere that asks for rest is placed on its surface: nothing to warn.
  Lines l;
  l.add("[bodies.ball]");
  l.add("type = \"rigid_body\"");
  l.add("shape = \"sphere\"");
  l.add("mass = 1.0");
  l.add("radius = 0.1");
  l.add("position = [0.0, 0.0, 0.07]");
  l.add("[impedances.floor]");
  l.add("type = \"kikuuwe_contact\"");
  l.add("body = \"ball\"");
  l.add("settle = true");
  check_generated({l.text(), 0, ""});
}

TEST_CASE("plausibility: no bundled scene warns") {
  const auto bundled = scene::bundled_scenes();
  REQUIRE(bundled.size() >= 10);
  for (const auto& [name, description] : bundled) {
    INFO(name);
    const scene::Scene s = scene::load_scene(name);
    std::string all;
    for (const auto& w : s.warnings) all += scene::format_warning(w) + "\n";
    INFO("warnings:\n" << all);
    CHECK(s.warnings.empty());
  }
}

TEST_CASE("plausibility: run and check report the warnings, --quiet silences stderr") {
  const fs::path dir = scratch("cli");
  std::mt19937 rng(7);
  const Generated bad = ball_on_plane(rng, Mistake::mu);
  const Generated good = ball_on_plane(rng, Mistake::none);
  std::ofstream(dir / "bad.toml") << bad.text;
  std::ofstream(dir / "good.toml") << good.text;
  const std::string located = "bad.toml:" + std::to_string(bad.line) + ":";

  auto o = stiction::testing::run_stiction(
      {"run", "bad.toml", "--out", "bad", "--no-video", "--no-plots"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains(located) && Contains(": warning: impedances.floor.mu: "));
  const nlohmann::json summary = read_json(dir / "bad" / "summary.json");
  REQUIRE(summary.contains("warnings"));
  REQUIRE(summary["warnings"].size() == 1);
  const nlohmann::json& w = summary["warnings"][0];
  CHECK(w["file"] == "bad.toml");
  CHECK(w["line"] == bad.line);
  CHECK(w["column"].get<int>() >= 1);
  CHECK(w["key"] == "impedances.floor.mu");
  CHECK_THAT(w["text"].get<std::string>(), Contains("mu = "));

  o = stiction::testing::run_stiction(
      {"run", "bad.toml", "--out", "quiet", "--no-video", "--no-plots", "--quiet"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, !Contains("warning"));
  CHECK(read_json(dir / "quiet" / "summary.json")["warnings"].size() == 1);

  o = stiction::testing::run_stiction(
      {"run", "good.toml", "--out", "good", "--no-video", "--no-plots"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, !Contains("warning:"));
  const nlohmann::json clean = read_json(dir / "good" / "summary.json");
  REQUIRE(clean.contains("warnings"));
  CHECK(clean["warnings"].is_array());
  CHECK(clean["warnings"].empty());

  o = stiction::testing::run_stiction({"check", "bad.toml"}, dir);
  CHECK(o.code == 0);
  CHECK_THAT(o.out, Contains(located) && Contains(": warning: impedances.floor.mu: "));
  o = stiction::testing::run_stiction({"check", "bad.toml", "--json"}, dir);
  CHECK(o.code == 0);
  const auto json = nlohmann::json::parse(o.out.substr(o.out.find('{')));
  REQUIRE(json.contains("warnings"));
  REQUIRE(json["warnings"].size() == 1);
  CHECK(json["warnings"][0]["key"] == "impedances.floor.mu");
  CHECK(json["warnings"][0]["line"] == bad.line);
}
