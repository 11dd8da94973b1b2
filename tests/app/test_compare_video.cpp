// `stiction compare A B C --video` as a user runs it, on generated arm scenes: one
// compare.mp4 beside compare.png, and a bad [inset] in any scene refused before simulating.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "generated_scenes.hpp"
#include "run_stiction.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// A small, cheap video: the test checks the wiring, tests/render the pictures.
std::string small_video(const std::string& inset) {
  return "\n[render]\nsize = [320, 180]\nfps = 20\nmsaa = 1\nshadow_map_size = 0\n" + inset;
}

}  // namespace

TEST_CASE("compare --video writes compare.mp4 beside compare.png", "[app][compare][video]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_compare_video_", "ok");
  std::vector<std::string> args{"compare"};
  for (int links = 2; links <= 4; ++links) {
    const std::string inset = links == 3 ? "[inset]\nsignals = [\"arm.theta.1\"]\n" : "";
    args.push_back(
        stiction::testing::write_scene(
            dir, "arm" + std::to_string(links),
            stiction::testing::arm_scene(links, 40u + unsigned(links), 0.3) + small_video(inset))
            .string());
  }
  args.insert(args.end(), {"--video", "--out", "c"});
  const auto o = stiction::testing::run_stiction(args, dir);
  INFO(o.out);
  REQUIRE(o.code == 0);
  CHECK_THAT(o.out, Contains("compare.png") && Contains("c/compare.mp4"));
  const fs::path mp4 = dir / "c" / "compare.mp4";
  REQUIRE(fs::exists(mp4));
  std::ifstream in(mp4, std::ios::binary);
  char head[8] = {};
  in.read(head, 8);
  CHECK(std::string(head + 4, 4) == "ftyp");
  CHECK_FALSE(fs::exists(dir / "c" / "video.mp4"));
}

TEST_CASE("compare --video: a bad [inset] is exit 2 at FILE:LINE:COL before any simulation",
          "[app][compare][video]") {
  const fs::path dir = stiction::testing::scratch_dir("stiction_test_compare_video_", "bad");
  const fs::path a = stiction::testing::write_scene(
      dir, "a", stiction::testing::arm_scene(2, 1u, 0.2) + small_video(""));
  const fs::path b =
      stiction::testing::write_scene(dir, "b",
                                     stiction::testing::arm_scene(2, 2u, 0.2) +
                                         small_video("[inset]\nsignals = [\"arm.theta.9\"]\n"));
  const auto o = stiction::testing::run_stiction(
      {"compare", a.string(), b.string(), "--video", "--out", "c"}, dir);
  INFO(o.out);
  CHECK(o.code == 2);
  CHECK_THAT(o.out, Contains("b.toml:") && Contains("inset.signals") &&
                        Contains("no signal named 'arm.theta.9'"));
  CHECK_THAT(o.out, !Contains("simulated"));
  CHECK_FALSE(fs::exists(dir / "c" / "compare.mp4"));
  // Without --video the same scenes compare (the renderer's tables are not read).
  const auto plain =
      stiction::testing::run_stiction({"compare", a.string(), b.string(), "--out", "d"}, dir);
  CHECK(plain.code == 0);
}
