// `stiction`: the command line of DESIGN section 3. Typed exceptions from the libraries
// become exit codes here and only here: 2 bad input, 3 instability (returned by run),
// 1 anything else.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <new>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli_checks.hpp"
#include "app/command_suggestion.hpp"
#include "app/commands.hpp"
#include "core/integrator.hpp"
#include "io/atomic_file.hpp"
#include "plot/figure.hpp"
#include "scene/toml_reader.hpp"
#include "sys/interrupt.hpp"
#include "sys/terminal_text.hpp"

namespace {

using namespace stiction;

// A report lost to a full disk or a closed pipe is a failure, not a success: stdout is
// flushed and checked before the exit code is final.
int finish_stdout(int code) {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::fprintf(stderr, "error: cannot write to standard output: %s\n", std::strerror(errno));
    return code == app::kExitOk ? app::kExitFailure : code;
  }
  return code;
}

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
  run->add_flag("--overwrite", run_args.overwrite,
                "write into a non-empty directory that is not a stiction output directory");
  CLI::Option* integrator_opt =
      run->add_option("--integrator", integrator, "integrator, overrides simulation.integrator")
          ->check(CLI::IsMember(core::integrator_names()));
  CLI::Option* dt_opt =
      run->add_option("--dt", dt, "step size in s, overrides simulation.dt")->check(app::finite_positive());
  CLI::Option* duration_opt = run->add_option("--duration", duration,
                                              "simulated time in s, overrides simulation.duration")
                                  ->check(app::finite_positive());
  double tolerance = 0.0;
  CLI::Option* tolerance_opt =
      run->add_option("--tolerance", tolerance,
                      "local error bound per state entry; runs the adaptive integrator --integrator "
                      "names (rk4_adaptive, sdirk2, sdirk4), rk4_adaptive by default")
          ->check(app::finite_positive());
  run->add_option("--set", run_args.overrides,
                  "KEY=VALUE: set a dotted key of the scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  run->add_flag("--no-video", run_args.no_video, "do not render a video");
  run->add_flag("--no-plots", run_args.no_plots, "do not draw plots");
  run->add_flag("--frames", run_args.frames, "also write frames/NNNNNN.png");
  run->add_flag("--quiet", run_args.quiet, "print nothing but errors");
  run->add_flag("--force-step", run_args.force_step,
                "simulate even when the step is above the predicted instability limit");
  std::string plot_format;
  CLI::Option* plot_format_opt =
      run->add_option("--plot-format", plot_format,
                      "png, svg or pdf: the format of every plot (default: each plot's own, PNG)")
          ->check(CLI::IsMember({"png", "svg", "pdf"}));
  std::string accuracy;
  CLI::Option* accuracy_opt =
      run->add_option("--accuracy", accuracy,
                      "on or off: estimate the run's error with a companion run (default: on "
                      "when it costs little, docs/accuracy.md)")
          ->check(CLI::IsMember({"on", "off"}));

  std::string check_scene;
  CLI::App* check = cli.add_subcommand("check", "validate a scene, print its state layout and dt advice");
  check->add_option("SCENE", check_scene, "bundled scene name or path to a .toml file")->required();
  std::string check_graph;
  check->add_option("--graph", check_graph,
                    "also write the scene's network (Fig. 2 of the paper) as Graphviz DOT");
  bool check_json = false;
  check->add_flag("--json", check_json, "print the findings (or the errors) as JSON on stdout");

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
                    "comma-separated step sizes in s (default: from past the predicted limit down)")
      ->delimiter(',')
      ->check(app::finite_positive());
  study->add_option("--tolerances", study_args.tolerances,
                    "comma-separated tolerances for rk4_adaptive (default 1e-4 .. 1e-10)")
      ->delimiter(',')
      ->check(app::finite_positive());
  CLI::Option* reference_dt_opt =
      study->add_option("--reference-dt", reference_dt, "step of the rk4 reference (default scene dt / 16)")
          ->check(app::finite_positive());
  study->add_option("--repeats", study_args.repeats, "timing repeats per run, median kept (default 3)")
      ->check(CLI::Range(1, 100));
  study->add_option("--out", study_args.out, "output directory (default out/<scene name>/study/)");
  study->add_option("--set", study_args.overrides,
                    "KEY=VALUE: set a dotted key of the scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  study->add_flag("--quiet", study_args.quiet, "print nothing but errors");
  study->add_option("--target-error", study_args.target_error,
                    "relative accuracy a run must meet: event times (/ duration) and final values "
                    "(/ signal scale), in (0, 1) (default 1e-3)")
      ->check(app::finite_positive());

  app::CompareArguments compare_args;
  CLI::App* compare = cli.add_subcommand("compare",
                                         "run several scenes and overlay their signals in "
                                         "compare.png (--video: side by side in compare.mp4)");
  compare->add_option("SCENE", compare_args.scenes, "two or more bundled scene names or .toml paths")
      ->required();
  compare->add_option("--out", compare_args.out, "output directory (default out/compare/)");
  compare->add_option("--set", compare_args.overrides,
                      "KEY=VALUE: set a dotted key of every scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  compare->add_flag("--quiet", compare_args.quiet, "print nothing but errors");
  compare->add_flag("--video", compare_args.video,
                    "also write compare.mp4: the runs side by side, synchronized on time");
  compare->add_flag("--force-step", compare_args.force_step,
                    "simulate even when a step is above its predicted instability limit");
  compare->add_option("--signals", compare_args.signals,
                      "comma-separated signals or groups to compare, e.g. sphere.v.x,ground.slip")
      ->delimiter(',');
  double compare_duration = 0.0;
  CLI::Option* compare_duration_opt =
      compare->add_option("--duration", compare_duration, "simulated time in s of every run")
          ->check(CLI::PositiveNumber);
  std::string compare_format;
  CLI::Option* compare_format_opt =
      compare->add_option("--plot-format", compare_format, "png (default), svg or pdf")
          ->check(CLI::IsMember({"png", "svg", "pdf"}));

  app::VerifyArguments verify_args;
  CLI::App* verify = cli.add_subcommand(
      "verify", "compare frames, figures and key numbers of scenes with a golden set (exit 4 on a "
                "difference)");
  verify->add_option("SCENE", verify_args.scenes,
                     "bundled scene names, .toml paths or directories of .toml files")
      ->required();
  verify->add_option("--golden", verify_args.golden, "golden set directory (one folder per scene)")
      ->required();
  verify->add_flag("--update", verify_args.update, "write or refresh the golden set and say what changed");
  verify->add_option("--at", verify_args.at,
                     "comma-separated frame times in s (default: the scene's [verify] at, else "
                     "first frame, each event, last frame)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  verify->add_option("--set", verify_args.overrides,
                     "KEY=VALUE: set a dotted key of every scene to a TOML value (repeatable)")
      ->allow_extra_args(false);
  verify->add_option("--out", verify_args.out, "report directory (default out/verify/)");
  verify->add_option("-j,--jobs", verify_args.jobs, "scenes verified at once (default: one per core)")
      ->check(CLI::Range(1, 256));
  verify->add_flag("--quiet", verify_args.quiet, "print nothing but errors and the verdict");
  verify->add_flag("--force-step", verify_args.force_step,
                   "simulate even when a step is above its predicted instability limit");

  app::SweepArguments sweep_args;
  double sweep_dt = 0.0, sweep_duration = 0.0;
  CLI::App* sweep = cli.add_subcommand(
      "sweep",
      "run a scene over a grid of --set values; writes sweep.csv, sweep.md, sweep.png, sweep.svg");
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
  sweep->add_flag("--overwrite", sweep_args.overwrite,
                  "replace the table of another sweep (or write into a foreign directory)");
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
  sweep->add_flag("--force-step", sweep_args.force_step,
                  "simulate points whose step is above the predicted instability limit");

  // A first word that is no command is a typo or a missing command: say which was meant
  // (`stiction rn`: did you mean 'run'?) instead of CLI11's "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> commands;
    for (const CLI::App* sub : cli.get_subcommands({})) commands.push_back(sub->get_name());
    if (std::find(commands.begin(), commands.end(), argv[1]) == commands.end()) {
      std::fprintf(stderr, "%s\n", app::unknown_command_message(argv[1], commands).c_str());
      return app::kExitBadInput;
    }
  }
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
    if (plot_format_opt->count() > 0) run_args.plot_format = plot::parse_format(plot_format);
    if (accuracy_opt->count() > 0) run_args.accuracy = accuracy == "on";
    return app::run_command(run_args);
  }
  if (*compare) {
    if (compare_duration_opt->count() > 0) compare_args.duration = compare_duration;
    if (compare_format_opt->count() > 0) compare_args.plot_format = plot::parse_format(compare_format);
    return app::compare_command(compare_args);
  }
  if (*verify) return app::verify_command(verify_args);
  if (*sweep) {
    if (sweep_dt_opt->count() > 0) sweep_args.dt = sweep_dt;
    if (sweep_duration_opt->count() > 0) sweep_args.duration = sweep_duration;
    return app::sweep_command(sweep_args);
  }
  if (*study) {
    if (reference_dt_opt->count() > 0) study_args.reference_dt = reference_dt;
    return app::study_command(study_args);
  }
  if (*check) return app::check_command(check_scene, check_graph, check_json);
  if (*scenes) return app::scenes_command();
  return app::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  stiction::sys::install_interrupt_handlers();
  try {
    const int code = finish_stdout(dispatch(argc, argv));
    // A command that finished before it polled the flag (check, scenes) still reports the
    // signal: the user asked it to stop, and it must not look like a success.
    if (stiction::sys::interrupted() && code == stiction::app::kExitOk) return stiction::sys::interrupt_exit_code();
    return code;
  } catch (const stiction::sys::Interrupted&) {
    std::fprintf(stderr, "interrupted by %s; nothing written\n", stiction::sys::interrupt_signal_name());
    return stiction::sys::interrupt_exit_code();
  } catch (const scene::InputError& e) {
    // Messages quote names and values from the user's files: escaped for the terminal.
    std::fprintf(stderr, "%s\n", stiction::sys::terminal_safe(e.what()).c_str());
    return app::kExitBadInput;
  } catch (const io::IoError& e) {
    std::fprintf(stderr, "error: %s\n", stiction::sys::terminal_safe(e.what()).c_str());
    return app::kExitFailure;
  } catch (const std::bad_alloc&) {
    // A bare "std::bad_alloc" said nothing (issue 39): name the cause and what to reduce.
    std::fprintf(stderr,
                 "error: out of memory: the run needs more memory than this process may use "
                 "(ulimit -v, a job's memory limit, or the machine's); each contact point "
                 "takes about 51 kB, each output row 8 bytes a column, each sweep point about "
                 "370 bytes before it runs (docs/limits.md): reduce contacts, output_rate or "
                 "points; the earlier outputs in --out are untouched\n");
    return app::kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", stiction::sys::terminal_safe(e.what()).c_str());
    return app::kExitFailure;
  }
}
