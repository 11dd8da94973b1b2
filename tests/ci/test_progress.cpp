// Progress for CI logs: with stderr not a terminal, run, study, compare and verify write
// plain lines (a start line, lines on the way, an end line), never a carriage return or an
// escape sequence; --quiet leaves stderr empty.
#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "ci_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void expect_plain_lines(const SplitOutcome& o, const std::string& start, const std::string& end) {
  INFO(o.err);
  CHECK(o.err.find('\r') == std::string::npos);
  CHECK(o.err.find('\033') == std::string::npos);
  CHECK_THAT(o.err, Contains(start));
  CHECK_THAT(o.err, Contains(end));
  CHECK(o.err.find(start) < o.err.rfind(end));
}

}  // namespace

TEST_CASE("progress: run writes start, 10% steps and end lines to a log, and --quiet silences") {
  const fs::path dir = scratch_dir("stiction_test_ci_progress_", "run");
  write_text(dir / "ball.toml", ball_scene("ball"));
  const SplitOutcome o = run_split({"run", "ball.toml", "--out", "out", "--no-plots"}, dir);
  REQUIRE(o.code == 0);
  expect_plain_lines(o, "simulate ball: start", "simulate ball: done in");
  expect_plain_lines(o, "render video: start", "render video: done in");
  // Every tenth of the simulation gets a line (the run is far shorter than 10 s).
  int tenths = 0;
  for (const std::string& line : lines_of(o.err)) {
    if (line.rfind("simulate ball: ", 0) == 0 && line.find("% after") != std::string::npos)
      ++tenths;
  }
  CHECK(tenths == 9);

  const SplitOutcome quiet =
      run_split({"run", "ball.toml", "--out", "out", "--no-plots", "--quiet"}, dir);
  REQUIRE(quiet.code == 0);
  CHECK(quiet.err.empty());
  CHECK(quiet.out.empty());
}

TEST_CASE("progress: study and compare write plain lines to a log") {
  const fs::path dir = scratch_dir("stiction_test_ci_progress_", "study");
  write_text(dir / "ball.toml", ball_scene("ball"));
  write_text(dir / "ball2.toml", ball_scene("ball2", 0.2));
  const SplitOutcome study =
      run_split({"study", "ball.toml", "--integrators", "rk4,euler", "--dts", "1e-4,5e-5",
                 "--reference-dt", "2.5e-5", "--repeats", "1", "--out", "study"},
                dir);
  REQUIRE(study.code == 0);
  expect_plain_lines(study, "study: start ball.toml", "study: done in");
  CHECK_THAT(study.err, Contains("study: rk4 dt 0.0001: "));

  const SplitOutcome compare =
      run_split({"compare", "ball.toml", "ball2.toml", "--out", "cmp"}, dir);
  REQUIRE(compare.code == 0);
  expect_plain_lines(compare, "simulate ball: start", "simulate ball2: done in");

  const SplitOutcome quiet =
      run_split({"compare", "ball.toml", "ball2.toml", "--out", "cmp", "--quiet"}, dir);
  REQUIRE(quiet.code == 0);
  CHECK(quiet.err.empty());
}
