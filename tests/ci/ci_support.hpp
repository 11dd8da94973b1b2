// Scenes the CI tests generate, and running the binary with stdout and stderr apart.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "run_stiction.hpp"

namespace stiction::testing {

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SplitOutcome {
  int code = -1;
  std::string out, err;
};

// Runs the binary with stdout and stderr in files (stderr is then not a terminal).
inline SplitOutcome run_split(const std::vector<std::string>& args,
                              const std::filesystem::path& cwd) {
  std::string command = "cd ";
  command += shell_quote(cwd.string());
  command += " && ";
  command += shell_quote(STICTION_BINARY);
  for (const auto& a : args) {
    command += ' ';
    command += shell_quote(a);
  }
  command += " >.stdout 2>.stderr";
  const int status = std::system(command.c_str());
  SplitOutcome o;
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  o.out = read_text(cwd / ".stdout");
  o.err = read_text(cwd / ".stderr");
  return o;
}

// A sphere launched along a frictional floor: it slips, sticks (rolls) and rolls on; one
// stick event. Every table `run` reads is present, with a small render and a fixed camera
// that sees FRAME_WIDTH_M metres across at the sphere's depth. `mu`, `x0` and the plot
// colour are what the verify tests change; `name` may be long.
inline constexpr double kFrameWidthM = 1.6;

inline std::string ball_scene(const std::string& name, double mu = 0.3, double x0 = 0.0,
                              const std::string& colour = "#0072b2") {
  std::ostringstream s;
  s.precision(17);
  s << "name = \"" << name << "\"\n"
    << "description = \"a ball that slips, then rolls\"\n"
    << "gravity = [0.0, 0.0, -9.8]\n\n"
    << "[simulation]\ndt = 1e-4\nduration = 0.5\n\n"
    << "[bodies.ball]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"sphere\"\nradius = 0.2\n"
    << "position = [" << x0 << ", 0.0, 0.2]\nvelocity = [1.0, 0.0, 0.0]\n\n"
    << "[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\nnormal = [0.0, 0.0, "
       "1.0]\n"
    << "stiffness = 1e6\ndamping = 100.0\nmu = " << mu << "\n\n"
    << "[render]\nsize = [320, 180]\nfps = 8\nmsaa = 1\nshadow_map_size = 256\n\n"
    // Horizontal field of view 2 atan(16/9 tan 20 deg) = 65.8 deg: at a distance d the
    // frame is 1.293 d wide; d = kFrameWidthM / 1.293.
    << "[camera]\nposition = [0.0, " << -kFrameWidthM / 1.2938
    << ", 0.2]\ntarget = [0.0, 0.0, 0.2]\n"
    << "fov = 40\n\n"
    << "[overlay]\nsignal = \"ground.slip\"\nlabel = \"slip\"\nunit = \"m/s\"\n\n"
    << "[[plots]]\nname = \"motion\"\nsize = [400, 300]\n"
    << "  [[plots.panels]]\n  signals = [\"ball.v.x\", \"ground.slip.x\"]\n"
    << "  colors = [\"" << colour << "\", \"#d55e00\"]\n";
  return s.str();
}

}  // namespace stiction::testing
