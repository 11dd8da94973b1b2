#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "core/simulation.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"
#include "scene/scene.hpp"

namespace stiction::app {
namespace fs = std::filesystem;

int run_command(const RunArguments& args) {
  scene::Scene scene = scene::load_scene(args.scene, args.overrides);
  core::RunOptions& run = scene.run;
  if (args.integrator) run.integrator = *args.integrator;
  if (args.dt) run.dt = *args.dt;
  if (args.duration) run.duration = *args.duration;

  const fs::path out = args.out.empty() ? fs::path("out") / scene.name : fs::path(args.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the output directory: " + ec.message());

  core::RunResult result;
  {
    std::unique_ptr<ProgressBar> bar;
    core::ProgressCallback progress;
    if (!args.quiet && ::isatty(STDERR_FILENO)) {
      bar = std::make_unique<ProgressBar>(run.duration);
      progress = [&bar](double fraction) { bar->update(fraction); };
    }
    result = core::simulate(*scene.network, run, progress);
  }

  io::RunDescription description;
  description.scene = scene.name;
  description.integrator = run.integrator;
  description.dt = run.dt;
  description.duration = run.duration;
  description.output_rate = run.output_rate;
  description.state_dim = scene.network->state_dim();
  // A quarter of the step is a first guess that clears most explicit stability limits
  // (RK4's limit scales with dt, and a factor 4 leaves room for stiff transients).
  if (result.instability) description.suggested_dt = run.dt / 4.0;

  const auto summary = io::make_summary(description, result);
  io::write_csv(result.trajectory, out / "trajectory.csv");
  io::write_summary(summary, out / "summary.json");

  if (result.instability) {
    const auto& inst = *result.instability;
    std::fprintf(stderr,
                 "error: numerical instability at t = %.6g s in '%s' (%s) with %s, dt = %g s; "
                 "try a smaller step, e.g. --dt %g\n",
                 inst.time, inst.component.c_str(), inst.reason.c_str(), run.integrator.c_str(),
                 run.dt, *description.suggested_dt);
    return kExitUnstable;
  }
  if (!args.quiet) {
    std::printf("%s: %s, dt = %g s, %ld steps, %d rows in %.3f s\n", scene.name.c_str(),
                run.integrator.c_str(), run.dt, result.steps, result.trajectory.row_count(),
                result.wall_seconds);
    for (const auto& [contact, entry] : summary["events"].items()) {
      if (entry["stick_time"].is_null()) {
        std::printf("  %s: no stick\n", contact.c_str());
      } else {
        std::printf("  %s: stick at t = %.6g s\n", contact.c_str(), entry["stick_time"].get<double>());
      }
    }
    std::printf("  wrote %s and %s\n", (out / "trajectory.csv").c_str(), (out / "summary.json").c_str());
  }
  return kExitOk;
}

}  // namespace stiction::app
