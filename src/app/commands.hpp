// The subcommands of `stiction` (DESIGN section 3). Each returns the process exit code or
// throws: scene::InputError (2), io::IoError and anything else (1); main maps them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "plot/figure.hpp"

namespace stiction::app {

// Exit codes (DESIGN section 3).
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitUnstable = 3;
// `verify` found a difference from the golden set.
inline constexpr int kExitMismatch = 4;
// Ctrl-C during the render: the video so far is kept as video.partial.mp4 (128 + SIGINT,
// the shell's convention for a command ended by Ctrl-C).
inline constexpr int kExitInterrupted = 130;

struct RunArguments {
  std::string scene;
  std::string out;  // empty: out/<scene name>/
  bool overwrite = false;  // --overwrite: write into a non-empty directory without a manifest
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;  // an adaptive integrator's (rk4_adaptive by default)
  std::vector<std::string> overrides;
  bool quiet = false;
  bool no_video = false, no_plots = false, frames = false;
  std::optional<plot::Format> plot_format;  // --plot-format: overrides every plot's format
  bool force_step = false;  // --force-step: run a step the guard predicts unstable
  // --accuracy on|off: force the companion run of the error estimate (docs/accuracy.md);
  // empty: on when it costs little.
  std::optional<bool> accuracy;
};

// `stiction compare SCENE SCENE...`: runs each scene (no video) and writes OUT/compare.png.
// A scene argument may carry overrides of its own: "sphere_roll@ground.mu=0.2@sphere.mass=1"
// (KEY=VALUE as for --set, each after an '@'). Runs are labelled by scene name plus the
// overrides in which they differ from the others.
struct CompareArguments {
  std::vector<std::string> scenes;
  std::string out;                     // empty: out/compare/
  std::vector<std::string> overrides;  // applied to every scene
  std::vector<std::string> signals;    // empty: the default comparison
  std::optional<double> duration;
  std::optional<plot::Format> plot_format;
  bool quiet = false;
  bool force_step = false;  // --force-step
  bool video = false;       // --video: OUT/compare.mp4, the runs side by side
};

// `stiction study SCENE`: speed against accuracy of the integrators (src/app/study.hpp).
struct StudyArguments {
  std::string scene;
  std::string out;                      // empty: out/<scene name>/study/
  std::vector<std::string> integrators; // empty: all
  std::vector<double> dts;              // empty: around the predicted limits (study_grid.hpp)
  std::vector<double> tolerances;       // empty: 1e-4 .. 1e-10 for rk4_adaptive
  std::optional<double> reference_dt;   // empty: scene dt / 16
  int repeats = 3;
  std::vector<std::string> overrides;
  bool quiet = false;
  double target_error = 1e-3;  // relative accuracy a run must meet (event times, final values)
};

// `stiction verify SCENE... --golden DIR`: frames, figures and key numbers of each scene
// against DIR/<scene>/ (src/app/verify_*.cpp, docs/ci.md).
struct VerifyArguments {
  std::vector<std::string> scenes;
  std::string golden;
  bool update = false;
  std::vector<double> at;              // empty: [verify] at, or the golden's frame times
  std::vector<std::string> overrides;  // applied to every scene
  std::string out;                     // empty: out/verify/
  int jobs = 0;                        // 0: one per core
  bool quiet = false;
  bool force_step = false;             // --force-step
};

// `stiction sweep SCENE --vary KEY=LIST...` (src/app/sweep.hpp, docs/sweeps.md).
struct SweepArguments {
  std::string scene;
  std::vector<std::string> vary;       // KEY=LIST, one per key
  bool zip = false;
  int jobs = 0;                        // 0: every core
  std::string keep = "summary";        // none | summary | all
  std::vector<std::string> record;     // signals whose final value is tabled (default all)
  std::vector<std::string> plot;       // table columns plotted (default: the stick times)
  std::string out;                     // empty: out/<scene name>/sweep/
  bool overwrite = false;              // --overwrite: replace another sweep's directory
  std::string shard;                   // K/N; empty: from SLURM_ARRAY_* or none
  std::string merge;                   // a directory of shards to merge instead of running
  std::vector<std::string> overrides;  // --set, applied to every point before its values
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;
  bool quiet = false;
  bool force_step = false;  // --force-step: simulate points the guard predicts unstable
};

int run_command(const RunArguments& args);
int verify_command(const VerifyArguments& args);
int sweep_command(const SweepArguments& args);
int study_command(const StudyArguments& args);
int compare_command(const CompareArguments& args);
// Validates a scene, prints its state layout, the stiffest elements and the predicted
// largest stable step of each fixed-step integrator; with a graph path, writes the network
// as Graphviz DOT. Reads [render], [camera], [overlay], [[plots]] and [verify] as `run` does
// (same errors, exit 2). With `json`, prints its findings (or the errors) as JSON on stdout.
int check_command(const std::string& scene, const std::string& graph_path = {}, bool json = false);
int scenes_command();

}  // namespace stiction::app
