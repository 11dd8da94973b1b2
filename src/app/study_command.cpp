// `stiction study SCENE`: runs the study (study.cpp), writes its reports (study_report.cpp)
// and prints the Markdown tables on stdout.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "scene/scene.hpp"
#include "services/heartbeat.hpp"
#include "services/study.hpp"
#include "text/number_text.hpp"

namespace stiction::app {
using namespace services;

int study_command(const StudyArguments& args) {
  StudyOptions options;
  options.scene = args.scene;
  options.overrides = args.overrides;
  options.integrators = args.integrators;
  options.dts = args.dts;
  options.tolerances = args.tolerances;
  options.reference_dt = args.reference_dt;
  options.repeats = args.repeats;
  options.target_error = args.target_error;

  // One line per run, on a terminal and in a log alike (each is a finished item, no bar),
  // between a start and an end line.
  // A watcher fills silences over 10 s (a long reference run).
  StudyLog log;
  std::unique_ptr<Heartbeat> heartbeat;
  const auto start = std::chrono::steady_clock::now();
  if (!args.quiet) {
    heartbeat = std::make_unique<Heartbeat>("study");
    heartbeat->line("start " + args.scene);
    log = [&heartbeat](const std::string& line) { heartbeat->line(line); };
  }
  const StudyResult result = run_study(options, log);
  if (heartbeat) {
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    heartbeat->line("done in " + text::significant(seconds, 3) + " s (" +
                    std::to_string(result.rows.size()) + " runs)");
    heartbeat.reset();
  }

  const std::filesystem::path out = args.out.empty()
                                        ? std::filesystem::path("out") / result.scene / "study"
                                        : std::filesystem::path(args.out);
  write_study(result, out);
  if (!args.quiet) {
    std::fputs(study_markdown(result).c_str(), stdout);
    std::printf("\nwrote %s, %s and %s\n", (out / "study.csv").c_str(), (out / "study.md").c_str(),
                (out / "work_precision.png").c_str());
  }
  return kExitOk;
}

}  // namespace stiction::app
