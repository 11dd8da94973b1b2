// `stiction`: the command line of DESIGN section 3. Typed exceptions from the libraries
// become exit codes here and only here: 2 bad input, 3 instability (returned by run),
// 1 anything else.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "core/integrator.hpp"
#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"

namespace {

using namespace stiction;

int dispatch(int argc, char** argv) {
  CLI::App cli{"stiction: simulator of mechanical systems with Coulomb friction "
               "(Kikuuwe & Yamamoto's modular RK4 architecture)",
               "stiction"};
  cli.set_version_flag("--version", std::string("stiction ") + STICTION_VERSION);
  cli.require_subcommand(1);

  app::RunArguments run_args;
  double dt = 0.0, duration = 0.0;
  std::string integrator;
  CLI::App* run = cli.add_subcommand("run", "simulate a scene; write trajectory.csv and summary.json");
  run->add_option("SCENE", run_args.scene, "bundled scene name or path to a .toml file")->required();
  run->add_option("--out", run_args.out, "output directory (default out/<scene name>/)");
  CLI::Option* integrator_opt =
      run->add_option("--integrator", integrator, "integrator, overrides simulation.integrator")
          ->check(CLI::IsMember(core::integrator_names()));
  CLI::Option* dt_opt =
      run->add_option("--dt", dt, "step size in s, overrides simulation.dt")->check(CLI::PositiveNumber);
  CLI::Option* duration_opt = run->add_option("--duration", duration,
                                              "simulated time in s, overrides simulation.duration")
                                  ->check(CLI::PositiveNumber);
  double tolerance = 0.0;
  CLI::Option* tolerance_opt =
      run->add_option("--tolerance", tolerance,
                      "local error bound per state entry; selects the integrator rk4_adaptive")
          ->check(CLI::PositiveNumber);
  run->add_option("--set", run_args.overrides,
                  "KEY=VALUE: set a dotted key of the scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  run->add_flag("--no-video", run_args.no_video, "do not render a video");
  run->add_flag("--no-plots", run_args.no_plots, "do not draw plots");
  run->add_flag("--frames", run_args.frames, "also write frames/NNNNNN.png");
  run->add_flag("--quiet", run_args.quiet, "print nothing but errors");

  std::string check_scene;
  CLI::App* check = cli.add_subcommand("check", "validate a scene, print its state layout and dt advice");
  check->add_option("SCENE", check_scene, "bundled scene name or path to a .toml file")->required();
  std::string check_graph;
  check->add_option("--graph", check_graph,
                    "also write the scene's network (Fig. 2 of the paper) as Graphviz DOT");

  CLI::App* scenes = cli.add_subcommand("scenes", "list the bundled scenes");

  app::StudyArguments study_args;
  double reference_dt = 0.0;
  CLI::App* study = cli.add_subcommand(
      "study", "speed against accuracy of the integrators on a scene; writes study.csv, study.md, "
               "work_precision.png");
  study->add_option("SCENE", study_args.scene, "bundled scene name or path to a .toml file")->required();
  study->add_option("--integrators", study_args.integrators, "comma-separated integrators (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(core::integrator_names()));
  study->add_option("--dts", study_args.dts,
                    "comma-separated step sizes in s (default: scene dt x 8, 4, 2, 1, 1/2, ... pruned)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  study->add_option("--tolerances", study_args.tolerances,
                    "comma-separated tolerances for rk4_adaptive (default 1e-4 .. 1e-10)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  CLI::Option* reference_dt_opt =
      study->add_option("--reference-dt", reference_dt, "step of the rk4 reference (default scene dt / 16)")
          ->check(CLI::PositiveNumber);
  study->add_option("--repeats", study_args.repeats, "timing repeats per run, median kept (default 3)")
      ->check(CLI::Range(1, 100));
  study->add_option("--out", study_args.out, "output directory (default out/<scene name>/study/)");
  study->add_option("--set", study_args.overrides,
                    "KEY=VALUE: set a dotted key of the scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  study->add_flag("--quiet", study_args.quiet, "print nothing but errors");

  app::CompareArguments compare_args;
  CLI::App* compare = cli.add_subcommand(
      "compare", "run several scenes (no video) and overlay their signals in compare.png");
  compare->add_option("SCENE", compare_args.scenes, "two or more bundled scene names or .toml paths")
      ->required();
  compare->add_option("--out", compare_args.out, "output directory (default out/compare/)");
  compare->add_option("--set", compare_args.overrides,
                      "KEY=VALUE: set a dotted key of every scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  compare->add_flag("--quiet", compare_args.quiet, "print nothing but errors");

  app::SweepArguments sweep_args;
  double sweep_dt = 0.0, sweep_duration = 0.0;
  CLI::App* sweep = cli.add_subcommand(
      "sweep", "run a scene over a grid of --set values; writes sweep.csv, sweep.md, sweep.png");
  sweep->add_option("SCENE", sweep_args.scene, "bundled scene name or path to a .toml file");
  sweep->add_option("--vary", sweep_args.vary,
                    "KEY=v1,v2,... or KEY=start:stop:count[:log] (repeatable: a grid)")
      ->allow_extra_args(false);
  sweep->add_flag("--zip", sweep_args.zip, "pair the --vary lists element-wise instead of a grid");
  sweep->add_option("-j,--jobs", sweep_args.jobs, "threads (default: every core)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("--keep", sweep_args.keep, "per-point outputs: none, summary (default) or all")
      ->check(CLI::IsMember({"none", "summary", "all"}));
  sweep->add_option("--record", sweep_args.record,
                    "comma-separated signals whose final value is tabled (default: all)")
      ->delimiter(',');
  sweep->add_option("--plot", sweep_args.plot,
                    "comma-separated table columns to plot (default: the stick times)")
      ->delimiter(',');
  sweep->add_option("--out", sweep_args.out, "output directory (default out/<scene name>/sweep/)");
  sweep->add_option("--shard", sweep_args.shard,
                    "K/N: run points K, K+N, ... (default from SLURM_ARRAY_TASK_ID/COUNT)");
  sweep->add_option("--merge", sweep_args.merge, "merge the sweep.shard-K.csv of DIR into sweep.csv");
  sweep->add_option("--set", sweep_args.overrides,
                    "KEY=VALUE: set a dotted key of the scene for every point (repeatable)")
      ->allow_extra_args(false);
  CLI::Option* sweep_dt_opt =
      sweep->add_option("--dt", sweep_dt, "step size in s, overrides simulation.dt")
          ->check(CLI::PositiveNumber);
  CLI::Option* sweep_duration_opt =
      sweep->add_option("--duration", sweep_duration, "simulated time in s")->check(CLI::PositiveNumber);
  bool sweep_no_video = false;  // a sweep never renders; accepted so `run` lines carry over
  sweep->add_flag("--no-video", sweep_no_video, "accepted for symmetry with run (a sweep never renders)");
  sweep->add_flag("--quiet", sweep_args.quiet, "print nothing but errors");

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with code 0; every other parse error is bad input.
    const int code = cli.exit(e);
    return code == 0 ? app::kExitOk : app::kExitBadInput;
  }

  if (*run) {
    if (integrator_opt->count() > 0) run_args.integrator = integrator;
    if (dt_opt->count() > 0) run_args.dt = dt;
    if (duration_opt->count() > 0) run_args.duration = duration;
    if (tolerance_opt->count() > 0) run_args.tolerance = tolerance;
    return app::run_command(run_args);
  }
  if (*sweep) {
    if (sweep_dt_opt->count() > 0) sweep_args.dt = sweep_dt;
    if (sweep_duration_opt->count() > 0) sweep_args.duration = sweep_duration;
    return app::sweep_command(sweep_args);
  }
  if (*compare) return app::compare_command(compare_args);
  if (*study) {
    if (reference_dt_opt->count() > 0) study_args.reference_dt = reference_dt;
    return app::study_command(study_args);
  }
  if (*check) return app::check_command(check_scene, check_graph);
  if (*scenes) return app::scenes_command();
  return app::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const scene::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return app::kExitBadInput;
  } catch (const io::IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return app::kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return app::kExitFailure;
  }
}
