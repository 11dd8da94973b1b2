// `stiction verify SCENE... --golden DIR [--update] [--at T,...] [--set K=V]... [--out DIR]`:
// every scene is loaded and checked first (exit 2 on bad input, as `run`), then verified on
// one thread per core (src/app/verify_scene.cpp); the verdicts go to stdout and to
// OUT/report.md, report.html and junit.xml. Exit 0 when everything matches, 4 on a
// difference, 1 when a scene could not be verified (rendering, I/O).
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "app/commands.hpp"
#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"
#include "services/progress.hpp"
#include "services/run_support.hpp"
#include "services/step_guard.hpp"
#include "services/owned_files.hpp"
#include "services/verify_golden.hpp"
#include "services/verify_report.hpp"
#include "services/verify_scene.hpp"
#include "text/number_text.hpp"

namespace stiction::app {
using namespace services;
namespace fs = std::filesystem;
namespace {

// A directory argument stands for the .toml files in it, in name order.
std::vector<std::string> expand(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const std::string& a : args) {
    std::error_code ec;
    if (!fs::is_directory(a, ec)) {
      out.push_back(a);
      continue;
    }
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(a, ec)) {
      if (e.path().extension() == ".toml") files.push_back(e.path().string());
    }
    if (files.empty())
      throw scene::InputError("error: " + a + ": no .toml scene files in this directory");
    std::sort(files.begin(), files.end());
    out.insert(out.end(), files.begin(), files.end());
  }
  return out;
}

VerifyJob prepare(const std::string& name, const VerifyArguments& args) {
  VerifyJob job;
  job.scene = scene::load_scene(name, args.overrides);
  apply_overrides(job.scene, {});
  job.render = render::read_render_settings(job.scene);
  // The figures `run` draws: the same specs, labels and units.
  const std::vector<core::ColumnInfo> columns = core::column_infos(*job.scene.network);
  job.plots = plot::read_plot_specs(job.scene.document, job.scene.path.string(), columns);
  if (job.plots.empty()) job.plots = plot::default_plot_specs(columns);
  job.settings = read_verify_settings(job.scene.document, job.scene.run.duration);
  for (double t : args.at) {
    if (t > job.scene.run.duration) {
      throw scene::InputError("error: --at " + text::shortest(t) + ": after the end of " +
                              job.scene.name + " (duration " +
                              text::shortest(job.scene.run.duration) + " s)");
    }
  }
  job.at = args.at;
  // Only regular files are read, and golden.json names only files inside its set (exit 2).
  check_golden_set(fs::path(args.golden) / job.scene.name);
  if (!args.update && !fs::exists(fs::path(args.golden) / job.scene.name / "golden.json")) {
    throw scene::InputError(
        "error: " + (fs::path(args.golden) / job.scene.name / "golden.json").string() +
        ": no golden set for scene '" + job.scene.name + "'; create it with `stiction verify " +
        name + " --golden " + args.golden + " --update`");
  }
  return job;
}

void print_verdict(const SceneVerdict& v, bool update, const fs::path& out) {
  if (!v.error.empty()) {
    std::printf("%s: ERROR: %s\n", v.scene.c_str(), v.error.c_str());
    return;
  }
  if (update) {
    int same = 0;
    for (const VerifyItem& i : v.items) same += i.status == ItemStatus::unchanged;
    std::printf("%s: golden set %s (%zu items, %d unchanged)\n", v.scene.c_str(),
                same == static_cast<int>(v.items.size()) ? "unchanged" : "updated", v.items.size(),
                same);
    for (const VerifyItem& i : v.items) {
      if (i.status == ItemStatus::unchanged) continue;
      std::printf("  %s %s: %s (%s)\n", status_name(i.status), i.name.c_str(), i.what.c_str(),
                  i.detail.c_str());
      for (const std::string& d : i.differences) std::printf("    %s\n", d.c_str());
    }
    return;
  }
  int mismatches = 0;
  for (const VerifyItem& i : v.items) mismatches += i.status == ItemStatus::mismatch;
  std::printf("%s: %s (%zu items, %d differ)\n", v.scene.c_str(), mismatches ? "FAILED" : "passed",
              v.items.size(), mismatches);
  for (const VerifyItem& i : v.items) {
    if (i.status != ItemStatus::mismatch) continue;
    std::printf("  MISMATCH %s: %s: %s\n", i.name.c_str(), i.what.c_str(), i.detail.c_str());
    if (!i.diff.empty())
      std::printf("    diff: %s\n", (out / i.diff).c_str());
    else if (!i.actual.empty())
      std::printf("    actual: %s\n", (out / i.actual).c_str());
    const std::size_t shown = std::min<std::size_t>(i.differences.size(), 10);
    for (std::size_t k = 0; k < shown; ++k) std::printf("    %s\n", i.differences[k].c_str());
    if (i.differences.size() > shown) {
      std::printf("    ... %zu more in the report\n", i.differences.size() - shown);
    }
  }
}

}  // namespace

int verify_command(const VerifyArguments& args) {
  // Everything is read and checked before the first simulation: bad input is exit 2 at once.
  std::vector<VerifyJob> jobs;
  std::set<std::string> names;
  for (const std::string& name : expand(args.scenes)) {
    jobs.push_back(prepare(name, args));
    if (!names.insert(jobs.back().scene.name).second) {
      throw scene::InputError("error: " + name + ": a second scene named '" +
                              jobs.back().scene.name + "' (golden sets are kept per scene name)");
    }
  }
  // The step guard for every scene before the first simulation: a golden set made at a step
  // predicted unstable would record an accident (exit 3, nothing written).
  for (VerifyJob& job : jobs) {
    const StepGuard guard = guard_step(job.scene, args.force_step);
    if (guard.refusal) {
      print_refusal(job.scene.name, guard);
      return kExitUnstable;
    }
    if (guard.warning && !args.quiet) {
      std::fprintf(stderr, "warning: %s: %s\n", job.scene.name.c_str(), guard.warning->c_str());
    }
  }
  const fs::path out = args.out.empty() ? fs::path("out") / "verify" : fs::path(args.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the report directory: " + ec.message());
  // Evidence of an earlier verification would sit beside the new one: its images go (only
  // those, by their names; never through a link), the rest of the directory is the user's.
  for (const VerifyJob& job : jobs) {
    const fs::path evidence = out / job.scene.name;
    if (!fs::is_directory(fs::symlink_status(evidence, ec))) continue;
    std::vector<fs::path> doomed;
    for (const auto& e : fs::directory_iterator(evidence, ec)) {
      const std::string name = e.path().filename().string();
      if (name.ends_with(".actual.png") || name.ends_with(".golden.png") || name.ends_with(".diff.png"))
        doomed.push_back(e.path());
    }
    for (const fs::path& p : doomed) remove_owned_file(p);
    fs::remove(evidence, ec);  // if now empty
  }

  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const int workers =
      std::min<int>(args.jobs > 0 ? args.jobs : cores, static_cast<int>(jobs.size()));
  std::vector<SceneVerdict> verdicts(jobs.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  int done = 0;
  std::unique_ptr<ProgressBar> progress;
  if (!args.quiet)
    progress = std::make_unique<ProgressBar>(args.update ? "verify --update" : "verify");
  const auto work = [&] {
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      verdicts[i] = verify_scene(jobs[i], args.golden, out, args.update);
      std::lock_guard lock(progress_mutex);
      ++done;
      if (progress) {
        progress->items(done, static_cast<int>(jobs.size()),
                        verdicts[i].scene + (verdicts[i].failed() ? " failed" : " ok"));
      }
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (progress) progress->finish(std::to_string(jobs.size()) + " scenes");
  progress.reset();

  bool error = false, mismatch = false;
  for (const SceneVerdict& v : verdicts) {
    error = error || !v.error.empty();
    mismatch = mismatch || v.failed();
    if (!args.quiet || v.failed()) print_verdict(v, args.update, out);
  }
  if (!args.update) {
    write_verify_reports(verdicts, args.golden, out);
    if (!args.quiet || mismatch) {
      std::printf("report: %s, %s, %s\n", (out / "report.md").c_str(),
                  (out / "report.html").c_str(), (out / "junit.xml").c_str());
    }
  }
  std::fflush(stdout);
  if (error) return kExitFailure;
  return mismatch ? kExitMismatch : kExitOk;
}

}  // namespace stiction::app
