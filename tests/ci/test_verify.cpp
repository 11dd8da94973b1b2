// `stiction verify`: a golden set made with --update verifies (exit 0); moving the body by
// 1% of the frame width, changing the friction coefficient by 5% and changing a plot colour
// each fail with exit 4, a diff image that shows the change, a report and a JUnit file that
// an XML parser reads. Pictures are the same bytes run after run.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "ci_support.hpp"
#include "image/png.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

// Pixels the diff image marks as beyond tolerance (pure red, brightness by the difference).
long red_pixels(const fs::path& diff_png) {
  const stiction::image::Image diff = stiction::image::read_png(diff_png);
  long n = 0;
  for (int y = 0; y < diff.height; ++y) {
    for (int x = 0; x < diff.width; ++x) {
      const std::uint8_t* p = diff.data(x, y);
      n += p[0] >= 128 && p[1] == 0 && p[2] == 0;
    }
  }
  return n;
}

// The JUnit file parsed by Python's XML parser: "<tests> <failures>".
std::string junit_counts(const fs::path& junit) {
  const fs::path out = junit.parent_path() / "junit_counts.txt";
  const std::string command =
      "python3 -c \"import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
      "assert r.tag == 'testsuites'; cases = list(r.iter('testcase')); "
      "print(len(cases), sum(1 for c in cases if c.find('failure') is not None))\" " +
      shell_quote(junit.string()) + " > " + shell_quote(out.string());
  REQUIRE(std::system(command.c_str()) == 0);
  std::string counts = read_text(out);
  while (!counts.empty() && (counts.back() == '\n' || counts.back() == '\r')) counts.pop_back();
  return counts;
}

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A changed scene must fail: exit 4, a report, a JUnit file with `failing` failed cases,
// and a diff image with red pixels for each item in `images`.
void expect_failure(const fs::path& dir, const std::string& variant, const std::string& text,
                    const std::vector<std::string>& images, int failing) {
  const fs::path scene_dir = dir / variant;
  fs::create_directories(scene_dir);
  write_text(scene_dir / "ball.toml", text);
  const fs::path report = dir / ("report_" + variant);
  const SplitOutcome o = run_split({"verify", (scene_dir / "ball.toml").string(), "--golden",
                                    "golden", "--out", report.string()},
                                   dir);
  INFO(variant << ":\n" << o.out << o.err);
  CHECK(o.code == 4);
  CHECK_THAT(o.out, Contains("ball: FAILED"));
  for (const std::string& item : images) {
    const fs::path diff = report / "ball" / (item + ".diff.png");
    INFO(item);
    REQUIRE(fs::exists(diff));
    CHECK(fs::exists(report / "ball" / (item + ".actual.png")));
    CHECK(fs::exists(report / "ball" / (item + ".golden.png")));
    CHECK(red_pixels(diff) > 50);
  }
  CHECK_THAT(read_text(report / "report.md"), Contains("MISMATCH"));
  const std::string html = read_text(report / "report.html");
  for (const std::string& item : images) CHECK_THAT(html, Contains("ball/" + item + ".diff.png"));
  CHECK(junit_counts(report / "junit.xml") == "5 " + std::to_string(failing));
}

}  // namespace

TEST_CASE(
    "verify: --update makes a golden set that verifies, and three kinds of change each fail") {
  const fs::path dir = scratch_dir("stiction_test_ci_verify_", "changes");
  write_text(dir / "ball.toml", ball_scene("ball"));
  SplitOutcome o = run_split({"verify", "ball.toml", "--golden", "golden", "--update"}, dir);
  INFO(o.out << o.err);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("added frame_000"));
  CHECK_THAT(o.out, Contains("added figure_motion"));
  // First frame, the first stick and slip (one video frame), last frame.
  CHECK(files_in(dir / "golden" / "ball") ==
        std::vector<std::string>{"figure_motion.png", "frame_000.png", "frame_001.png",
                                 "frame_002.png", "golden.json"});

  o = run_split({"verify", "ball.toml", "--golden", "golden", "--out", "report_same"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("ball: passed (5 items, 0 differ)"));
  CHECK(junit_counts(dir / "report_same" / "junit.xml") == "5 0");
  CHECK(fs::is_empty(dir / "report_same") == false);
  CHECK_FALSE(fs::exists(dir / "report_same" / "ball"));  // no evidence without a mismatch

  o = run_split({"verify", "ball.toml", "--golden", "golden", "--update"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("ball: golden set unchanged"));

  // The body moved by 1% of the frame width: every frame differs, and the final position.
  expect_failure(dir, "moved", ball_scene("ball", 0.3, 0.01 * kFrameWidthM),
                 {"frame_000", "frame_001", "frame_002"}, 4);
  // Friction 5% higher: the ball sticks earlier; the events and the figure change. The frames
  // do not: the ball ends 0.66 mm (0.13 pixel) away, and the stuck ball's slip speed reads
  // 0 in both (below the contact's stick threshold; it used to show rounding noise).
  expect_failure(dir, "friction", ball_scene("ball", 0.3 * 1.05), {"figure_motion"}, 2);
  // One plot colour: only the figure differs.
  expect_failure(dir, "colour", ball_scene("ball", 0.3, 0.0, "#009e73"), {"figure_motion"}, 1);

  // --update after the intended change says what changed.
  o = run_split({"verify", "colour/ball.toml", "--golden", "golden", "--update"}, dir);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("changed figure_motion"));
  CHECK(run_split({"verify", "colour/ball.toml", "--golden", "golden"}, dir).code == 0);
}

TEST_CASE("verify: the same scene gives the same bytes run after run (frames, figures, reports)") {
  const fs::path dir = scratch_dir("stiction_test_ci_verify_", "bytes");
  write_text(dir / "ball.toml", ball_scene("ball"));
  REQUIRE(run_split({"verify", "ball.toml", "--golden", "g1", "--update", "--quiet"}, dir).code ==
          0);
  REQUIRE(run_split({"verify", "ball.toml", "--golden", "g2", "--update", "--quiet"}, dir).code ==
          0);
  const auto files = files_in(dir / "g1" / "ball");
  REQUIRE(files == files_in(dir / "g2" / "ball"));
  for (const std::string& f : files) {
    INFO(f);
    CHECK(read_text(dir / "g1" / "ball" / f) == read_text(dir / "g2" / "ball" / f));
  }
  // Failing reports are byte-identical too (no times, no host names).
  write_text(dir / "moved.toml", ball_scene("ball", 0.3, 0.02));
  REQUIRE(
      run_split({"verify", "moved.toml", "--golden", "g1", "--out", "r1", "--quiet"}, dir).code ==
      4);
  REQUIRE(
      run_split({"verify", "moved.toml", "--golden", "g1", "--out", "r2", "--quiet"}, dir).code ==
      4);
  for (const char* f : {"report.md", "report.html", "junit.xml", "ball/frame_001.diff.png"}) {
    INFO(f);
    CHECK(read_text(dir / "r1" / f) == read_text(dir / "r2" / f));
  }
}

TEST_CASE(
    "verify: many generated scenes in a directory, in parallel, with --at, and bad input is exit "
    "2") {
  const fs::path dir = scratch_dir("stiction_test_ci_verify_", "many");
  fs::create_directories(dir / "scenes");
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> mu(0.1, 0.5), x0(-0.2, 0.2);
  for (int i = 0; i < 4; ++i) {
    const std::string name =
        "scene_" + std::to_string(i) + "_with_a_long_name_" + std::string(30, 'a' + i);
    write_text(dir / "scenes" / (name + ".toml"), ball_scene(name, mu(rng), x0(rng)));
  }
  SplitOutcome o = run_split(
      {"verify", "scenes", "--golden", "golden", "--update", "-j", "2", "--at", "0.1,0.4"}, dir);
  INFO(o.out << o.err);
  REQUIRE(o.code == 0);
  o = run_split({"verify", "scenes", "--golden", "golden", "-j", "2", "--out", "report"}, dir);
  REQUIRE(o.code == 0);
  CHECK(junit_counts(dir / "report" / "junit.xml") == "16 0");  // 2 frames, 1 figure, numbers x 4
  // Progress lines in the log, start to end.
  CHECK_THAT(o.err, Contains("verify: start"));
  CHECK_THAT(o.err, Contains("verify: done in"));
  CHECK(o.err.find('\r') == std::string::npos);

  // Bad input: no golden set, a time after the end, an unknown scene.
  write_text(dir / "new.toml", ball_scene("new_scene"));
  o = run_split({"verify", "new.toml", "--golden", "golden"}, dir);
  CHECK(o.code == 2);
  CHECK_THAT(o.err, Contains("no golden set for scene 'new_scene'"));
  CHECK(
      run_split({"verify", "new.toml", "--golden", "golden", "--update", "--at", "9"}, dir).code ==
      2);
  CHECK(run_split({"verify", "no_such_scene", "--golden", "golden"}, dir).code == 2);
  CHECK(run_split({"verify", "new.toml"}, dir).code == 2);  // --golden is required
}

TEST_CASE("verify: two runs of each bundled scene give identical frame and figure bytes") {
  const fs::path dir = scratch_dir("stiction_test_ci_verify_", "bundled");
  // Cut to 0.4 s of simulated time: its first and last video frame, and every figure.
  const std::vector<std::string> common{"--set", "simulation.duration=0.4", "--at", "0,0.4",
                                        "--quiet"};
  const fs::path scenes = fs::path(STICTION_SOURCE_DIR) / "scenes";
  for (const char* golden : {"g1", "g2"}) {
    std::vector<std::string> args{"verify", scenes.string(), "--golden", golden, "--update"};
    args.insert(args.end(), common.begin(), common.end());
    const SplitOutcome o = run_split(args, dir);
    INFO(o.out << o.err);
    REQUIRE(o.code == 0);
  }
  int scenes_seen = 0, images = 0;
  for (const auto& entry : fs::directory_iterator(dir / "g1")) {
    ++scenes_seen;
    const std::string scene = entry.path().filename().string();
    const auto files = files_in(entry.path());
    REQUIRE(files == files_in(dir / "g2" / scene));
    for (const std::string& f : files) {
      INFO(scene << "/" << f);
      images += f.size() > 4 && f.substr(f.size() - 4) == ".png";
      CHECK(read_text(entry.path() / f) == read_text(dir / "g2" / scene / f));
    }
  }
  int bundled = 0;
  for (const auto& entry : fs::directory_iterator(scenes))
    bundled += entry.path().extension() == ".toml";
  CHECK(scenes_seen == bundled);
  CHECK(images >= 3 * bundled);  // two frames and at least one figure each
}

TEST_CASE("verify: its figures are the ones run writes (the same pixels)") {
  // The same rows (thinned as run thins them), the same events with their labels ("slide
  // 2.45 s", not "ground.0 slip"), the same layout: services::run_figure for both.
  const fs::path dir = scratch_dir("stiction_test_ci_verify_", "as_run");
  for (const std::string scene : {"sphere_roll", "box_push_slide"}) {
    const std::vector<std::string> cut{"--set", "simulation.duration=2.6"};
    std::vector<std::string> run{"run", scene,     "--no-video", "--accuracy",
                                 "off", "--quiet", "--out",      (dir / ("run_" + scene)).string()};
    run.insert(run.end(), cut.begin(), cut.end());
    const SplitOutcome r = run_split(run, dir);
    INFO(r.out << r.err);
    REQUIRE(r.code == 0);
    std::vector<std::string> verify{"verify",   scene,  "--golden", "golden",
                                    "--update", "--at", "0",        "--quiet"};
    verify.insert(verify.end(), cut.begin(), cut.end());
    const SplitOutcome v = run_split(verify, dir);
    INFO(v.out << v.err);
    REQUIRE(v.code == 0);
    int figures = 0;
    for (const auto& entry : fs::directory_iterator(dir / ("run_" + scene) / "plots")) {
      const std::string name = entry.path().stem().string();
      INFO(scene << ": " << name);
      const fs::path golden = dir / "golden" / scene / ("figure_" + name + ".png");
      REQUIRE(fs::exists(golden));
      const stiction::image::Image a = stiction::image::read_png(entry.path());
      const stiction::image::Image b = stiction::image::read_png(golden);
      REQUIRE(a.width == b.width);
      REQUIRE(a.height == b.height);
      CHECK(a.pixels == b.pixels);
      ++figures;
    }
    CHECK(figures >= 1);
  }
}
