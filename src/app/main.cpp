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
#include "plot/figure.hpp"
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
  std::string plot_format;
  CLI::Option* plot_format_opt =
      run->add_option("--plot-format", plot_format,
                      "png, svg or pdf: the format of every plot (default: each plot's own, PNG)")
          ->check(CLI::IsMember({"png", "svg", "pdf"}));

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
    return app::run_command(run_args);
  }
  if (*compare) {
    if (compare_duration_opt->count() > 0) compare_args.duration = compare_duration;
    if (compare_format_opt->count() > 0) compare_args.plot_format = plot::parse_format(compare_format);
    return app::compare_command(compare_args);
  }
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
