// A bad value of any new contact key, through `stiction check` and `stiction run`: exit code
// 2 and "FILE:LINE:COL: error: KEY: ..." on stderr.
#include <fstream>

#include "run_stiction.hpp"

using stiction::testing::run_stiction;
using stiction::testing::scratch_dir;

TEST_CASE("cli: bad contact keys give exit 2 and FILE:LINE:COL: error:", "[contacts][cli]") {
  const auto dir = scratch_dir("stiction_contacts_", "cli");
  const std::string head =
      "[bodies.b]\ntype = \"rigid_body\"\nshape = \"box\"\nmass = 1.0\nsize = [0.2, 0.2, 0.1]\n"
      "[impedances.c]\ntype = \"kikuuwe_contact\"\nbody = \"b\"\n";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"points = [[1.0, 2.0]]", "bad.toml:9:11: error: impedances.c.points"},
      {"extent = { max = [0.0, nan] }", "bad.toml:9:24: error: impedances.c.extent.max"},
      {"initial_e = [0.0]", "bad.toml:9:13: error: impedances.c.initial_e"},
      {"settle = \"yes\"", "bad.toml:9:10: error: impedances.c.settle"},
      {"belt_speed = \"3*\"", "bad.toml:9:"},
      {"tilt = [1.0]", "bad.toml:9:8: error: impedances.c.tilt"},
  };
  for (const auto& [line, expected] : cases) {
    INFO(line);
    std::ofstream(dir / "bad.toml") << head << line << "\n";
    for (const auto& args :
         {std::vector<std::string>{"check", "bad.toml"},
          std::vector<std::string>{"run", "bad.toml", "--no-video", "--no-plots"}}) {
      const auto outcome = run_stiction(args, dir);
      CHECK(outcome.code == 2);
      CHECK_THAT(outcome.out, Catch::Matchers::Contains(expected));
    }
  }
  std::filesystem::remove_all(dir);
}
