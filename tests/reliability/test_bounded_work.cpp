// Bounded work (issue 25): `check` on scenes too large for its dense step analysis (a
// 1000-link arm, a box on 1000 contact points) answers at once and says what it skipped;
// a signal during the analysis of a scene it does analyse ends it; the step suggestion's
// trials are bounded even for a duration of 1e305 s; a stop set during a run is seen before
// the next step. The scenes are generated here (seeded).
// The child's time bounds are hang guards (the old program takes minutes), not timings.
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "child.hpp"
#include "core/simulation.hpp"
#include "generated_scene.hpp"
#include "scene/scene.hpp"

namespace fs = std::filesystem;
using namespace stiction::testing;

namespace {

// n links of random length with joint friction on every joint: 3 n states.
std::string arm_scene(int links, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> length(0.1, 0.25), limit(0.1, 0.5);
  std::ostringstream s;
  s << "name = \"arm" << links << "\"\ngravity = [0.0, 0.0, 0.0]\n"
    << "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = 0.2\noutput_rate = 500.0\n"
    << "[bodies.arm]\ntype = \"planar_arm\"\nlinks = [\n";
  for (int i = 0; i < links; ++i) s << "  { length = " << length(rng) << ", width = 0.02, mass = 0.2 },\n";
  s << "]\n";
  for (int i = 0; i < links; ++i) {
    s << "[impedances.joint" << i << "_friction]\ntype = \"kikuuwe_friction\"\nbody = \"arm\"\njoint = " << i
      << "\nstiffness = 5000.0\ndamping = 1.0\nforce_limit = " << limit(rng) << "\nstick_threshold = 0.02\n";
  }
  return s.str();
}

// A box resting on `points` random points of its bottom face (each a friction contact with
// 1/points of the stiffness, so the whole box is as stiff as on one point of 1e6 N/m).
std::string box_scene(int points, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-0.2, 0.2), y(-0.1, 0.1);
  std::ostringstream s;
  s.precision(17);
  s << "name = \"box" << points << "\"\ngravity = [0.0, 0.0, -9.8]\n"
    << "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = 0.2\noutput_rate = 500.0\n"
    << "[bodies.box]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"box\"\nsize = [0.4, 0.2, 0.2]\n"
    << "position = [0.0, 0.0, 0.1]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\n"
    << "stiffness = " << 1e6 / points << "\ndamping = " << 1e3 / points << "\nmu = 0.5\npoints = [\n";
  for (int i = 0; i < points; ++i) s << "  [" << x(rng) << ", " << y(rng) << ", -0.1],\n";
  s << "]\n";
  return s.str();
}

fs::path write(const fs::path& dir, const std::string& text) {
  const fs::path p = dir / "scene.toml";
  std::ofstream(p) << text;
  return p;
}

// `check --json` on the scene in `dir`, which must answer (exit 0) within `guard`.
nlohmann::json check_json(const fs::path& dir, std::chrono::seconds guard, const char* what) {
  Child child({"check", "--json", "scene.toml"}, dir);
  const int code = child.wait(guard);  // hang guard
  INFO(child.err());
  REQUIRE(code == 0);
  std::printf("check on %s: %.2f s\n", what, child.seconds_waited);
  return nlohmann::json::parse(child.out());
}

// `check --json` on the scene answers (hang guard 60 s) with the analysis skipped.
void check_skips(const fs::path& dir, int expected_states) {
  const auto j = check_json(dir, std::chrono::seconds(60), "a network too large to analyse");
  CHECK(j["state_dim"] == expected_states);
  REQUIRE(j.contains("analysis"));
  CHECK(j["analysis"]["skipped"] == true);
  CHECK(j["analysis"]["state_dim"] == expected_states);
  CHECK(j["analysis"]["max_states"].get<int>() < expected_states);
  CHECK(j["analysis"]["reason"].get<std::string>().find("states") != std::string::npos);
  CHECK(j["step_limits"].empty());
}

}  // namespace

TEST_CASE("check on a 1000-link arm answers and says it skipped the step analysis", "[bounded]") {
  const fs::path dir = scratch_dir("bounded", "arm1000");
  write(dir, arm_scene(1000, 25));
  check_skips(dir, 3000);  // two per link, one per joint friction
}

TEST_CASE("check on a box with 1000 contact points answers and says it skipped the step analysis", "[bounded]") {
  const fs::path dir = scratch_dir("bounded", "box1000");
  write(dir, box_scene(1000, 26));
  check_skips(dir, 13 + 2 * 1000);  // the rigid body, two friction states per point
}

TEST_CASE("run on the 1000-link arm is not held up by the step guard and says the step was not checked", "[bounded]") {
  const fs::path dir = scratch_dir("bounded", "arm1000_run");
  write(dir, arm_scene(1000, 27));
  Child child({"run", "scene.toml", "--out", "out", "--no-plots", "--no-video"}, dir);
  const int code = child.wait(std::chrono::seconds(60));
  INFO(child.err());
  REQUIRE(code == 0);
  const auto summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  REQUIRE(summary.contains("step_check"));
  CHECK(summary["step_check"]["verdict"] == "not_checked");
  CHECK(summary["step_check"]["states"] == 3000);
}

TEST_CASE("SIGTERM and SIGINT during check's step analysis end it", "[bounded]") {
  // 70 links, 210 states: analysed, for minutes; the signal comes after 2 s, well inside.
  for (const int sig : {SIGTERM, SIGINT}) {
    const fs::path dir = scratch_dir("bounded", sig == SIGTERM ? "check_term" : "check_int");
    write(dir, arm_scene(70, 28));
    Child child({"check", "scene.toml"}, dir);
    std::this_thread::sleep_for(std::chrono::seconds(2));
    REQUIRE(child.running());
    child.signal(sig);
    const int code = child.wait(std::chrono::seconds(5));  // hang guard; the old one took 19-38 s
    INFO(child.err());
    CHECK(code == 128 + sig);
    std::printf("check: exited %.3f s after %s\n", child.seconds_waited, sig == SIGTERM ? "SIGTERM" : "SIGINT");
  }
}

TEST_CASE("the step suggestion's trials are bounded for a step and duration near the largest double", "[bounded]") {
  // dt < duration, both huge: the trial at the candidate must not try to cover 1e305 s.
  for (unsigned seed : {1u, 2u}) {
    const fs::path dir = scratch_dir("bounded", "huge_dt_" + std::to_string(seed));
    SceneSpec spec;
    spec.seed = seed;
    spec.output_rate = 1e-303;
    spec.duration = 1e305;  // the scene valid on its own: one step per 10 rows of 1e303 s
    spec.dt = 1e304;
    write_scene(dir, spec);
    Child child({"run", "scene.toml", "--out", "out", "--no-plots", "--no-video", "--duration", "1e305", "--dt",
                 "1e304"},
                dir);
    const int code = child.wait(std::chrono::seconds(90));
    INFO(child.err());
    CHECK(code == 3);  // refused with a step to use, not an error from the trial itself
    CHECK(child.err().find("--dt ") != std::string::npos);
    CHECK(child.err().find("more than the limit") == std::string::npos);
  }
}

TEST_CASE("a contact with 100000 points is refused before allocating, with a located error", "[bounded][contact_points]") {
  // The old program ended in std::bad_alloc (exit 1), even with --no-plots.
  const fs::path dir = scratch_dir("bounded", "box100000");
  write(dir, box_scene(100000, 29));
  Child child({"run", "scene.toml", "--out", "out", "--no-plots", "--no-video"}, dir);
  const int code = child.wait(std::chrono::seconds(120));  // hang guard
  INFO(child.err());
  CHECK(code == 2);
  const std::string err = child.err();
  CHECK(err.find("scene.toml:") != std::string::npos);  // file:line:col
  CHECK(err.find("points") != std::string::npos);      // the key
  CHECK(err.find("100000 contact points") != std::string::npos);
  CHECK(err.find(" GB") != std::string::npos);         // the estimate
  CHECK(err.find("limit") != std::string::npos);
  CHECK(err.find("bad_alloc") == std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out" / "summary.json"));
}

TEST_CASE("study on a network too large for the step analysis says it has no prediction and goes on", "[bounded][study]") {
  // 150 points: 313 states, past the analysis' bound; the old study linearized it densely
  // (without its stop flag) for minutes.
  const fs::path dir = scratch_dir("bounded", "study_box150");
  write(dir, box_scene(150, 30));
  Child child({"study", "scene.toml", "--integrators", "rk4", "--repeats", "1", "--out", "study", "--set",
               "simulation.duration=0.01"},
              dir);
  const int code = child.wait(std::chrono::seconds(60));  // hang guard
  INFO(child.err() + child.out());
  REQUIRE(code == 0);
  const std::string report = read_text(dir / "study" / "study.md");
  CHECK(report.find("skipped") != std::string::npos);
  CHECK(report.find("313 states") != std::string::npos);
  CHECK((child.err() + child.out()).find("unstable above 0 s") == std::string::npos);
}

namespace {

// The keys of the top-level object `member` of a JSON text, in their order, joined by commas.
std::string top_level_keys_of(const std::string& text, const std::string& member) {
  struct Keys : nlohmann::json_sax<nlohmann::json> {
    std::string member, keys;
    int depth = 0;
    bool inside = false, next_is_member = false;
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override {
      ++depth;
      inside = inside || (depth == 2 && next_is_member);
      return true;
    }
    bool end_object() override {
      if (depth == 2) inside = false;
      --depth;
      return true;
    }
    bool start_array(std::size_t) override { ++depth; return true; }
    bool end_array() override { --depth; return true; }
    bool key(string_t& k) override {
      if (depth == 1) next_is_member = k == member;
      if (inside && depth == 2) {
        if (!keys.empty()) keys += ',';
        keys += k;
      }
      return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
      return false;
    }
  } keys;
  keys.member = member;
  nlohmann::json::sax_parse(text, &keys);
  return keys.keys;
}

}  // namespace

TEST_CASE("40000 springs on one mass: loading, run and summary stay linear in the elements", "[bounded][columns]") {
  // 120000 force columns on 6 states: the step analysis is cheap, so what is timed by the
  // hang guard is the per-element work. The old summary, accuracy report and load-time
  // plausibility check each searched every element per element: 78 s here; now about 5 s
  // on this machine (10000 springs: 2.6 s).
  const fs::path dir = scratch_dir("bounded", "springs40000");
  const int n = 40000;
  std::mt19937 rng(28);
  std::uniform_real_distribution<double> stiffness(1e-4, 1e-3), anchor(-1.0, 1.0);
  std::vector<double> k(n), ax(n);
  std::ostringstream s;
  s.precision(17);
  s << "name = \"springs\"\ngravity = [0.0, 0.0, 0.0]\n[simulation]\nintegrator = \"rk4\"\ndt = 1e-3\n"
    << "duration = 2e-3\noutput_rate = 1000.0\n[bodies.m]\ntype = \"point_mass\"\nmass = 1.0\n"
    << "position = [0.1, 0.0, 0.0]\n";
  for (int i = 0; i < n; ++i) {
    k[i] = stiffness(rng);
    ax[i] = anchor(rng);
    s << "[impedances.s" << i << "]\ntype = \"spring_damper\"\nbody = \"m\"\nother_point = [" << ax[i]
      << ", 0.0, 0.0]\nstiffness = " << k[i] << "\ndamping = 0.0\n";
  }
  write(dir, s.str());
  // --accuracy on: the companion run whose report has a final entry per column (left off by
  // default when it would cost more than 5 s, as under ASan, and then absent).
  Child child({"run", "scene.toml", "--out", "out", "--no-plots", "--no-video", "--quiet", "--accuracy", "on"},
              dir);
  const int code = child.wait(std::chrono::seconds(60));  // hang guard
  INFO(child.err());
  REQUIRE(code == 0);
  std::printf("run with %d springs: %.2f s\n", n, child.seconds_waited);
  // Parsed into std::map objects: an ordered_json object checks each new key against all the
  // others (120000^2 comparisons, 30 s of this test); the key order is read by SAX.
  const std::string text = read_text(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(text);
  const auto& final_row = summary.at("final");
  REQUIRE(final_row.size() == static_cast<std::size_t>(1 + 6 + 3 * n));
  // In the CSV's column order, each spring's force is -k (p - anchor) at the final state.
  std::ifstream csv(dir / "out" / "trajectory.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(top_level_keys_of(text, "final") == header);
  const double x = final_row.at("m.p.x").get<double>();
  for (const int i : {0, n / 2, n - 1}) {
    INFO("spring " << i);
    std::string column = "s";
    column += std::to_string(i);
    column += ".f.x";
    CHECK(final_row.at(column).get<double>() == Approx(-k[i] * (x - ax[i])).epsilon(1e-12));
  }
  // .at(): a missing key throws (a const operator[] on one is undefined behaviour).
  CHECK(summary.at("accuracy").at("final").size() == static_cast<std::size_t>(6 + 3 * n));
}

TEST_CASE("check on a 40-link arm stops at its work budget and names the integrators it left", "[bounded][budget]") {
  // 120 coupled states: under the 240 of the skip rule, but one radius costs 120^3. The whole
  // analysis took 197 s here; it now stops at the work budget (machine-independent units),
  // the scene's own integrator first, and says what it left.
  const fs::path dir = scratch_dir("bounded", "arm40");
  write(dir, arm_scene(40, 29));
  const auto j = check_json(dir, std::chrono::seconds(120), "a 40-link arm");
  CHECK(j["analysis"]["skipped"] == false);
  const double work = j["analysis"]["work"].get<double>();
  const double budget = j["analysis"]["work_budget"].get<double>();
  // The search stops at the first radius past the budget: one radius of 120 coupled states
  // (120^3 + 120^2) at most beyond it.
  CHECK(work > budget);
  CHECK(work <= budget + 120.0 * 120.0 * 120.0 + 120.0 * 120.0);
  int left = 0;
  for (const auto& [name, limit] : j["step_limits"].items()) {
    INFO(name);
    if (limit["analysed"] == false) {
      ++left;
      CHECK(limit["reason"].get<std::string>().find("work budget") != std::string::npos);
      CHECK_FALSE(limit.contains("unstable_above"));
    }
  }
  CHECK(left >= 1);
  CHECK(j["step_limits"].size() == 5);
}

TEST_CASE("check on a 10-link arm analyses every integrator within the budget", "[bounded][budget]") {
  const fs::path dir = scratch_dir("bounded", "arm10");
  write(dir, arm_scene(10, 30));
  const auto j = check_json(dir, std::chrono::seconds(120), "a 10-link arm");
  CHECK(j["analysis"]["work"].get<double>() <= j["analysis"]["work_budget"].get<double>());
  for (const auto& [name, limit] : j["step_limits"].items()) {
    INFO(name);
    CHECK(limit["analysed"] == true);
    CHECK(limit.contains("unbounded"));
  }
}

// Issue 39 item 3: `check` on a URDF chain whose joints have <limit> pushed the whole tree
// once per joint limit to find the mass each sees (n^2: 38 s at 5000 joints). Now only the
// bodies a push reaches are evaluated and the single-element figures are bounded in work
// (kMobilityWork), the rest named "not computed": 3000 joints answer at once (0.4 s here).
TEST_CASE("check on a long URDF chain with joint limits stays within its work bound", "[bounded][urdf]") {
  const fs::path dir = scratch_dir("bounded", "urdf_chain");
  const int joints = 3000;
  std::ostringstream urdf;
  const char* inertia = "<inertia ixx=\"0.001\" iyy=\"0.001\" izz=\"0.001\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>";
  urdf << "<robot name=\"chain\"><link name=\"l0\"><inertial><mass value=\"1\"/>" << inertia
       << "</inertial></link>\n";
  for (int i = 1; i <= joints; ++i) {
    urdf << "<link name=\"l" << i << "\"><inertial><origin xyz=\"0 0 -0.05\"/><mass value=\"0.1\"/>"
         << inertia << "</inertial></link>\n<joint name=\"j" << i
         << "\" type=\"revolute\"><parent link=\"l" << i - 1 << "\"/><child link=\"l" << i
         << "\"/><origin xyz=\"0 0 -0.1\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" "
            "effort=\"10\" velocity=\"1\"/></joint>\n";
  }
  urdf << "</robot>\n";
  std::ofstream(dir / "chain.urdf") << urdf.str();
  std::ofstream(dir / "chain.toml") << "[simulation]\ndt = 1e-4\nduration = 0.01\n"
                                       "[bodies.arm]\ntype = \"urdf\"\nfile = \"chain.urdf\"\n";
  Child child({"check", "chain.toml"}, dir, "urdf_chain");
  REQUIRE(child.wait(std::chrono::seconds(30)) == 0);
  const std::string out = child.out();
  // Every limit is named (a run of alike lines as its first line and "the same for N more,
  // FIRST to LAST"); the first ones with their mass, the rest past the bound.
  CHECK(out.find("arm.j1.limit (joint_limit): K = ") != std::string::npos);
  CHECK(out.find("arm.j1.limit (joint_limit): K = 1e+06; its effective mass was not computed") ==
        std::string::npos);
  const std::size_t over = out.find("its effective mass was not computed (bounded work");
  REQUIRE(over != std::string::npos);
  std::string last = "arm.j";  // appended piecewise: GCC 12 -Wrestrict false positive
  last += std::to_string(joints) + ".limit";
  CHECK(out.find(last, over) != std::string::npos);
}

TEST_CASE("a stop set during a run ends it before the next step, for every integrator",
          "[bounded]") {
  // A step of a large scene can take seconds (an adaptive step of 64 coincident bodies and
  // their 2016 pair contacts: 9 ms in Release, up to 0.7 s under the sanitizers), so a stop
  // (a signal, the fuzz targets' time budget) must be seen before the next step, not the
  // 64th (fuzz_pairs timed out in CI on exactly that). Generated scenes: a box on random
  // points, the progress callback (called after every step here: 40 steps of dt) sets the
  // flag after the third step.
  for (const std::string integrator : {"rk4", "rk4_adaptive", "implicit", "sdirk2"}) {
    INFO(integrator);
    const bool adaptive = integrator == "rk4_adaptive" || integrator == "sdirk2";
    std::string text = box_scene(7, 29);
    std::string line = "integrator = \"";  // appended: GCC 12's false -Wrestrict
    line += integrator + "\"";
    text.replace(text.find("integrator = \"rk4\""), 18, line);
    text.replace(text.find("duration = 0.2"), 14,
                 adaptive ? "duration = 4e-3\ntolerance = 1e-6" : "duration = 4e-3");
    stiction::scene::Scene scene =
        stiction::scene::load_scene(stiction::scene::SceneSource::from_text(text, "box7.toml"));
    std::atomic<bool> stop{false};
    stiction::core::RunOptions options = scene.run;
    options.stop = &stop;
    int reports = 0;
    const stiction::core::RunResult result =
        stiction::core::simulate(*scene.network, options, [&](double) {
          if (++reports == 3) stop = true;
        });
    CHECK(result.interrupted);
    CHECK(result.steps == 3);
  }
}
