// The subcommands of `stiction` (DESIGN section 3). Each returns the process exit code or
// throws: scene::InputError (2), io::IoError and anything else (1); main maps them.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace stiction::app {

// Exit codes (DESIGN section 3).
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitUnstable = 3;

struct RunArguments {
  std::string scene;
  std::string out;  // empty: out/<scene name>/
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::vector<std::string> overrides;
  bool quiet = false;
  // Accepted for the contract; rendering is not part of this build yet.
  bool no_video = false, no_plots = false, frames = false;
};

int run_command(const RunArguments& args);
int check_command(const std::string& scene);
int scenes_command();

}  // namespace stiction::app
