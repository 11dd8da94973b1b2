// Every new key with a bad value stops `stiction check` and `stiction run` with exit code 2
// and FILE:LINE:COL: error: naming the key.
#include <fstream>

#include "run_stiction.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using stiction::testing::run_stiction;
using stiction::testing::scratch_dir;

namespace {

struct BadValue {
  std::string text;      // the scene
  std::string location;  // "scene.toml:LINE:COL: error: KEY"
};

const std::string kArm =
    "[bodies.arm]\ntype = \"planar_arm\"\nlinks = [{length = 0.3, mass = 0.5}]\n";  // lines 1-3
const std::string kBall =
    "[bodies.ball]\ntype = \"rigid_body\"\nmass = 1\nshape = \"sphere\"\nradius = 0.1\n";  // lines
                                                                                           // 1-5

}  // namespace

TEST_CASE("sources cli: bad values of the new keys exit 2 with FILE:LINE:COL") {
  const auto dir = scratch_dir("stiction_sources_cli_", "bad");
  const std::vector<BadValue> cases{
      {kArm + "axis = [0, 0, 0]\n", "scene.toml:4:8: error: bodies.arm.axis"},
      {kArm + "axis = [1, 2]\n", "scene.toml:4:8: error: bodies.arm.axis"},
      {kArm + "[impedances.pd]\ntype = \"torque_source\"\nbody = \"arm\"\njoint = 0\n"
              "torque = \"-5*arm.theta.7\"\n",
       "scene.toml:8:14: error: impedances.pd.torque"},
      {kBall + "[impedances.push]\ntype = \"force_source\"\nbody = \"ball\"\nforce = [1, 2, "
               "3]\nframe = \"local\"\n",
       "scene.toml:10:9: error: impedances.push.frame"},
      {kBall + "[impedances.push]\ntype = \"force_source\"\nbody = \"ball\"\nforce = [1, 2]\n",
       "scene.toml:9:9: error: impedances.push.force"},
      {kBall + "[impedances.push]\ntype = \"force_source\"\nbody = \"ball\"\nforce = "
               "[\"ball.v.q\", 0, 0]\n",
       "scene.toml:9:11: error: impedances.push.force[0]"},
      {kBall + "[impedances.push]\ntype = \"force_source\"\nbody = \"ball\"\nforce = [1, 2, "
               "3]\npoint = \"top\"\n",
       "scene.toml:10:9: error: impedances.push.point"},
      // A source reading its own value, and two reading each other (an algebraic loop).
      {kBall + "[impedances.push]\ntype = \"force_source\"\nbody = \"ball\"\nforce = "
               "[0, \"-push.f.y\", 0]\n",
       "scene.toml:9:15: error: impedances.push.force[1]"},
      {kBall + "[impedances.a]\ntype = \"torque_source\"\nbody = \"ball\"\ntorque = \"b.tau\"\n"
               "[impedances.b]\ntype = \"torque_source\"\nbody = \"ball\"\ntorque = \"-a.tau\"\n",
       "scene.toml:13:12: error: impedances.b.torque"},
  };
  for (const auto& c : cases) {
    { std::ofstream(dir / "scene.toml") << c.text; }
    const std::vector<std::vector<std::string>> commands{
        {"check", "scene.toml"}, {"run", "scene.toml", "--no-video", "--no-plots", "--out", "out"}};
    for (const auto& args : commands) {
      const auto outcome = run_stiction(args, dir);
      INFO(args[0] << " on:\n" << c.text << "\noutput: " << outcome.out);
      CHECK(outcome.code == 2);
      CHECK_THAT(outcome.out, Contains(c.location));
    }
  }
}
