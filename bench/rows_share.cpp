// bench_rows_share: what the rows cost in one `stiction run` (issue 36 item 4). Runs a scene
// as `run --no-video` does (trajectory.csv streamed through io::CsvStream, the plots' thinned
// copy) and prints one JSON line:
//   wall            simulate + writing the rest of trajectory.csv (the commit), seconds
//   rows_wall       of it, the run loop's time on rows (RunResult::row_seconds) and the wait
//                   for the writer at the commit: what the rows add to the user's wait
//   cpu             process CPU time over the same span (both threads)
//   rows_cpu        rows_wall's main-thread part plus the CSV writer thread's CPU time
// Shares are rows_wall / wall and rows_cpu / cpu. bench/rows_share.py runs it per scene and
// integrator.
//
//   bench_rows_share SCENE [--integrator NAME] [--dt S] [--duration S] [--tolerance TOL]
//                    [--set KEY=VALUE]... [--out DIR]
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "scene/scene.hpp"
#include "services/run_service.hpp"
#include "services/run_support.hpp"
#include "services/streamed_rows.hpp"

namespace {

double cpu_seconds(clockid_t clock) {
  timespec ts{};
  ::clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_rows_share SCENE [--integrator NAME] [--dt S] [--duration S] "
               "[--tolerance TOL] [--set KEY=VALUE]... [--out DIR]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace stiction;
  namespace fs = std::filesystem;
  if (argc < 2) return usage();
  const std::string scene_name = argv[1];
  services::RunRequest request;
  std::vector<std::string> sets;
  fs::path out = fs::temp_directory_path() / ("stiction_rows_share_" + std::to_string(::getpid()));
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) return usage();
    const std::string v = argv[++i];
    if (a == "--integrator") request.overrides.integrator = v;
    else if (a == "--dt") request.overrides.dt = std::stod(v);
    else if (a == "--duration") request.overrides.duration = std::stod(v);
    else if (a == "--tolerance") request.overrides.tolerance = std::stod(v);
    else if (a == "--set") sets.push_back(v);
    else if (a == "--out") out = v;
    else return usage();
  }
  nlohmann::ordered_json j;
  j["scene"] = scene_name;
  try {
    services::PreparedRun prepared =
        services::prepare_run(scene::load_scene(scene_name, sets), request);
    services::guard_run(prepared, request);
    const core::RunOptions& run = prepared.scene.run;
    j["integrator"] = run.integrator;
    j["dt"] = run.dt;
    j["duration"] = run.duration;
    j["output_rate"] = run.output_rate;
    if (prepared.guard.refusal) {
      j["status"] = "refused";
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    fs::create_directories(out);
    core::RunResult result;
    double wall = 0.0, commit = 0.0, cpu = 0.0, main_cpu = 0.0, writer_cpu = 0.0;
    {
      services::StreamedRows rows(out / "trajectory.csv", prepared.columns, run,
                                  prepared.render_settings, true, false);
      const double cpu0 = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID);
      const double main0 = cpu_seconds(CLOCK_THREAD_CPUTIME_ID);
      const auto t0 = std::chrono::steady_clock::now();
      result = services::simulate_scene(prepared.scene, false, &rows.sink());
      const auto t1 = std::chrono::steady_clock::now();
      rows.commit_csv();
      const auto t2 = std::chrono::steady_clock::now();
      cpu = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID) - cpu0;
      main_cpu = cpu_seconds(CLOCK_THREAD_CPUTIME_ID) - main0;
      wall = std::chrono::duration<double>(t2 - t0).count();
      commit = std::chrono::duration<double>(t2 - t1).count();
      writer_cpu = rows.csv_writer_cpu_seconds();
    }
    j["csv_bytes"] = fs::file_size(out / "trajectory.csv");
    fs::remove_all(out);
    j["status"] = result.instability ? "unstable" : "ok";
    j["steps"] = result.steps;
    j["rows"] = result.rows;
    j["wall"] = wall;
    j["rows_wall"] = result.row_seconds + commit;
    j["row_seconds"] = result.row_seconds;
    j["commit_wait"] = commit;
    j["cpu"] = cpu;
    j["main_cpu"] = main_cpu;
    j["writer_cpu"] = writer_cpu;
    j["rows_cpu"] = result.row_seconds + writer_cpu;
    j["wall_share"] = wall > 0.0 ? (result.row_seconds + commit) / wall : 0.0;
    j["cpu_share"] = cpu > 0.0 ? (result.row_seconds + writer_cpu) / cpu : 0.0;
  } catch (const std::exception& e) {
    j["status"] = "error";
    j["error"] = e.what();
  }
  std::printf("%s\n", j.dump().c_str());
  return 0;
}
