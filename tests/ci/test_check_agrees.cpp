// `check` accepts exactly what `run` accepts: a generated scene with every table `run` reads
// (bodies, contacts with an extent and `settle`, a force source, render, camera, overlay,
// plots), broken one value at a time (a seeded sample of lines and bad values), must give
// exit 2 from both commands or from neither.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "ci_support.hpp"

namespace fs = std::filesystem;
using namespace stiction::testing;

namespace {

std::string scene_text() {
  return ball_scene("a_generated_scene_for_check_and_run") +
         "\n[bodies.crate]\ntype = \"rigid_body\"\nmass = 2.0\nshape = \"box\"\n"
         "size = [0.2, 0.3, 0.1]\nposition = [2.0, 0.0, 0.05]\n"
         "[impedances.crate_floor]\ntype = \"kikuuwe_contact\"\nbody = \"crate\"\n"
         "stiffness = 1e6\ndamping = 500.0\nmu = 0.4\nsettle = true\n"
         "extent = { axis = [1.0, 0.0, 0.0], min = [1.0, -inf] }\n"
         "[impedances.push]\ntype = \"force_source\"\nbody = \"crate\"\n"
         "force = [\"2*t\", 0.0, 0.0]\npoint = [0.0, 0.0, 0.03]\n";
}

}  // namespace

TEST_CASE("check and run agree on every value they reject, over sampled broken values") {
  const std::vector<std::string> bad{"-1.0", "0", "\"x\"", "true", "[]", "inf", "nan",
                                     "9007199254740993", "1e-300", "[1.0, 2.0]"};
  std::vector<std::string> lines;
  {
    std::istringstream in(scene_text());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::vector<std::pair<std::size_t, std::string>> cases;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto eq = lines[i].find(" = ");
    if (eq == std::string::npos || lines[i].front() == '[' || lines[i].front() == '#') continue;
    for (const std::string& value : bad) cases.push_back({i, value});
  }
  std::mt19937 rng(20261130);
  std::shuffle(cases.begin(), cases.end(), rng);
  cases.resize(std::min<std::size_t>(cases.size(), 48));
  const fs::path dir = scratch_dir("stiction_test_ci_agree_", "cases");
  int rejected = 0;
  for (const auto& [line, value] : cases) {
    std::string text;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      text += (i == line ? l.substr(0, l.find(" = ") + 3) + value : l) + "\n";
    }
    write_text(dir / "broken.toml", text);
    const SplitOutcome check = run_split({"check", "broken.toml"}, dir);
    const SplitOutcome run = run_split({"run", "broken.toml", "--duration", "0.002", "--no-video",
                                        "--out", "out", "--quiet"},
                                       dir);
    INFO("line " << line + 1 << " set to " << value << ": " << lines[line] << "\ncheck ("
                 << check.code << "): " << check.err << "\nrun (" << run.code << "): " << run.err);
    CHECK((check.code == 2) == (run.code == 2));
    if (run.code == 2) {
      ++rejected;
      CHECK(check.err == run.err);  // the same located message
    }
  }
  // The sample breaks the scene more often than not: the test sees both kinds of case.
  CHECK(rejected > 10);
  CHECK(rejected < static_cast<int>(cases.size()));
}
