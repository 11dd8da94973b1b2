// `stiction study SCENE`: runs the study (study.cpp), writes its reports (study_report.cpp)
// and prints the Markdown tables on stdout.
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "app/commands.hpp"
#include "app/study.hpp"
#include "scene/scene.hpp"

namespace stiction::app {

int study_command(const StudyArguments& args) {
  StudyOptions options;
  options.scene = args.scene;
  options.overrides = args.overrides;
  options.integrators = args.integrators;
  options.dts = args.dts;
  options.tolerances = args.tolerances;
  options.reference_dt = args.reference_dt;
  options.repeats = args.repeats;

  StudyLog log;
  if (!args.quiet && ::isatty(STDERR_FILENO)) {
    log = [](const std::string& line) { std::fprintf(stderr, "study: %s\n", line.c_str()); };
  }
  const StudyResult result = run_study(options, log);

  const std::filesystem::path out =
      args.out.empty() ? std::filesystem::path("out") / result.scene / "study" : std::filesystem::path(args.out);
  write_study(result, out);
  if (!args.quiet) {
    std::fputs(study_markdown(result).c_str(), stdout);
    std::printf("\nwrote %s, %s and %s\n", (out / "study.csv").c_str(), (out / "study.md").c_str(),
                (out / "work_precision.png").c_str());
  }
  return kExitOk;
}

}  // namespace stiction::app
