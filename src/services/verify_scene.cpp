#include "services/verify_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "core/simulation.hpp"
#include "image/compare.hpp"
#include "image/png.hpp"
#include "io/atomic_file.hpp"
#include "io/summary.hpp"
#include "plot/figure.hpp"
#include "render/render_outputs.hpp"
#include "render/scene_view.hpp"
#include "services/owned_files.hpp"
#include "services/plot_outputs.hpp"
#include "services/render_loader.hpp"
#include "services/run_outputs.hpp"
#include "services/run_support.hpp"
#include "services/verify_golden.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr std::size_t kMaxEventNumbers = 50;  // per element, so chatter cannot flood the set
constexpr std::size_t kMaxEventFrames = 8;

std::string format(const char* pattern, double v) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

// The key numbers of a run: its status, its last row, its events.
json key_numbers(const nlohmann::ordered_json& summary) {
  json n = json::object();
  n["status"] = summary["status"];
  for (const auto& [column, value] : summary["final"].items()) n["final." + column] = value;
  for (const auto& [element, entry] : summary["events"].items()) {
    const std::string base = "events." + element;
    n[base + ".stick_time"] = entry["stick_time"];
    n[base + ".count"] = entry["events"].size();
    for (std::size_t i = 0; i < std::min(entry["events"].size(), kMaxEventNumbers); ++i) {
      const auto& e = entry["events"][i];
      n[base + "[" + std::to_string(i) + "]." + e["kind"].get<std::string>()] = e["time"];
    }
  }
  return n;
}

VerifyItem make_item(std::string kind, std::string name, std::string what) {
  VerifyItem item;
  item.kind = std::move(kind);
  item.name = std::move(name);
  item.what = std::move(what);
  return item;
}

std::string show(const json& v) {
  if (v.is_number_float()) return format("%.9g", v.get<double>());
  return v.dump();
}

// One line per key that differs (missing on one side, other text, or a number out of
// tolerance).
std::vector<std::string> number_differences(const json& actual, const json& golden,
                                            const VerifySettings& s) {
  std::set<std::string> keys;
  for (const auto& [k, v] : actual.items()) keys.insert(k);
  for (const auto& [k, v] : golden.items()) keys.insert(k);
  std::vector<std::string> out;
  for (const std::string& k : keys) {
    if (!actual.contains(k)) {
      out.push_back(k + ": missing (golden " + show(golden[k]) + ")");
      continue;
    }
    if (!golden.contains(k)) {
      out.push_back(k + ": not in the golden set (actual " + show(actual[k]) + ")");
      continue;
    }
    const json& a = actual[k];
    const json& g = golden[k];
    if (a.is_number() && g.is_number()) {
      const double av = a.get<double>(), gv = g.get<double>();
      const double diff = std::abs(av - gv);
      if (!(diff <= s.abs_tolerance + s.rel_tolerance * std::abs(gv))) {
        out.push_back(k + ": actual " + show(a) + ", golden " + show(g) + ", difference " +
                      format("%.3g", av - gv) +
                      (gv != 0.0 ? " (" + format("%.3g", diff / std::abs(gv)) + " relative)" : ""));
      }
    } else if (a != g) {
      out.push_back(k + ": actual " + show(a) + ", golden " + show(g));
    }
  }
  return out;
}

// Snapped to the video's frames, sorted, without duplicates.
std::vector<double> snap(const std::vector<double>& times, const render::FrameClock& clock) {
  std::vector<double> out;
  for (double t : times) {
    const long i =
        std::clamp(std::lround((t - clock.start) / clock.step), 0L, long(clock.count - 1));
    out.push_back(clock.time(static_cast<int>(i)));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// First frame, the first event of each kind of each element (at most kMaxEventFrames),
// last frame.
std::vector<double> default_times(const nlohmann::ordered_json& summary,
                                  const render::FrameClock& clock) {
  std::vector<double> times{clock.start};
  std::size_t events = 0;
  for (const auto& [element, entry] : summary["events"].items()) {
    std::set<std::string> kinds;
    for (const auto& e : entry["events"]) {
      if (events >= kMaxEventFrames) break;
      if (kinds.insert(e["kind"].get<std::string>()).second) {
        times.push_back(e["time"].get<double>());
        ++events;
      }
    }
  }
  times.push_back(clock.time(clock.count - 1));
  return times;
}

json read_manifest(const fs::path& file) {
  if (!fs::exists(file)) return json();
  std::ifstream in(file);
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw scene::InputError(file.string() + ": error: not a golden manifest: " + e.what());
  }
}

class SceneVerifier {
 public:
  // `stage`: where --update writes the new set (verify_golden.hpp); the old one is read from
  // `golden_dir`.
  SceneVerifier(VerifyJob& job, fs::path golden_dir, fs::path out_dir, bool update,
                fs::path stage = {})
      : job_(job),
        golden_(std::move(golden_dir)),
        stage_(std::move(stage)),
        out_(std::move(out_dir)),
        update_(update),
        manifest_(read_manifest(golden_ / "golden.json")) {
    options_.channel_tolerance = job.settings.pixel_tolerance;
    options_.max_fraction = job.settings.max_differing;
    options_.max_rms = job.settings.max_rms;
  }

  SceneVerdict run() {
    SceneVerdict verdict;
    verdict.scene = job_.scene.name;
    scene::Scene& scene = job_.scene;
    const core::RunResult result = core::simulate(*scene.network, scene.run);
    const nlohmann::ordered_json summary = io::make_summary(describe_run(scene), result);

    json next = json::object();
    next["scene"] = scene.name;
    next["frames"] = json::array();
    next["figures"] = json::array();
    if (job_.settings.frames) frames(result, summary, next, verdict);
    if (job_.settings.figures) figures(result, next, verdict);
    numbers(summary, next, verdict);
    if (update_) {
      removed(next, verdict);
      io::write_file_atomically(stage_ / "golden.json", next.dump(2) + "\n");
    }
    return verdict;
  }

 private:
  std::vector<double> frame_times(const nlohmann::ordered_json& summary,
                                  const render::FrameClock& clock) {
    if (!job_.at.empty()) return snap(job_.at, clock);
    if (!job_.settings.at.empty()) return snap(job_.settings.at, clock);
    if (!update_ && manifest_.contains("frames")) {
      std::vector<double> times;
      for (const auto& f : manifest_["frames"]) times.push_back(f["t"].get<double>());
      return times;
    }
    return snap(default_times(summary, clock), clock);
  }

  void frames(const core::RunResult& result, const nlohmann::ordered_json& summary, json& next,
              SceneVerdict& verdict) {
    const RenderedFrames rendered = render_frames_on_demand(
        job_.scene, result.trajectory, job_.render,
        [&](const render::FrameClock& clock) { return frame_times(summary, clock); },
        slip_event_times(result), slip_event_kinds(result));
    const std::vector<double>& times = rendered.times;
    std::map<int, double> golden_times;
    if (manifest_.contains("frames")) {
      int i = 0;
      for (const auto& f : manifest_["frames"]) golden_times[i++] = f["t"].get<double>();
    }
    for (std::size_t i = 0; i < times.size(); ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%03zu", i);
      const std::string file = std::string(name) + ".png";
      next["frames"].push_back({{"file", file}, {"t", times[i]}});
      VerifyItem item = make_item("frame", name, "frame at t = " + format("%.6g", times[i]) + " s");
      const image::Image& actual = rendered.images[i];
      const auto golden_t = golden_times.find(static_cast<int>(i));
      if (!update_ && golden_t != golden_times.end() &&
          std::abs(golden_t->second - times[i]) > 1e-9) {
        item.status = ItemStatus::mismatch;
        item.detail = "the golden frame shows t = " + format("%.6g", golden_t->second) + " s";
        write_evidence(item, actual, golden_ / file);
      } else {
        image_item(item, actual, golden_ / file);
      }
      verdict.items.push_back(std::move(item));
    }
    if (!update_ && golden_times.size() > times.size()) {
      VerifyItem item = make_item("frame", "frames", "frame count");
      item.status = ItemStatus::mismatch;
      item.detail = "the golden set has " + std::to_string(golden_times.size()) +
                    " frames, this run " + std::to_string(times.size());
      verdict.items.push_back(std::move(item));
    }
  }

  // The figures `run` writes (plot_outputs.hpp: the same rows, thinned as run thins them, the
  // same events, labels and layout), as PNG.
  void figures(const core::RunResult& result, json& next, SceneVerdict& verdict) {
    const core::Trajectory rows = plot_rows(result.trajectory);
    for (const plot::PlotSpec& spec : job_.plots) {
      const std::string name = "figure_" + spec.name;
      const std::string file = name + ".png";
      next["figures"].push_back({{"file", file}, {"name", spec.name}});
      VerifyItem item = make_item("figure", name, "figure " + spec.name);
      const image::Image actual = plot::render(run_figure(spec, result, rows));
      image_item(item, actual, golden_ / file);
      verdict.items.push_back(std::move(item));
    }
  }

  void numbers(const nlohmann::ordered_json& summary, json& next, SceneVerdict& verdict) {
    const json actual = key_numbers(summary);
    next["numbers"] = actual;
    VerifyItem item = make_item("numbers", "numbers", "key numbers (status, final state, events)");
    const bool have = manifest_.contains("numbers");
    const json golden = have ? manifest_["numbers"] : json::object();
    item.differences = number_differences(actual, golden, job_.settings);
    const std::string count = std::to_string(item.differences.size()) + " of " +
                              std::to_string(actual.size()) + " numbers differ";
    if (update_) {
      item.status = !have                      ? ItemStatus::added
                    : item.differences.empty() ? ItemStatus::unchanged
                                               : ItemStatus::changed;
      item.detail = have ? count : std::to_string(actual.size()) + " numbers";
      if (!have) item.differences.clear();  // all of them: nothing to tell
    } else if (!have) {
      item.status = ItemStatus::mismatch;
      item.detail = "no numbers in the golden set (run verify --update)";
    } else {
      item.status = item.differences.empty() ? ItemStatus::match : ItemStatus::mismatch;
      item.detail = count + format(" (tolerance: abs %g", job_.settings.abs_tolerance) +
                    format(" + rel %g)", job_.settings.rel_tolerance);
    }
    verdict.items.push_back(std::move(item));
  }

  // Golden files of the old set that the new one no longer lists: the new set (the stage)
  // lacks them; nothing is deleted here (names are checked by check_golden_set).
  void removed(const json& next, SceneVerdict& verdict) {
    std::set<std::string> kept;
    for (const char* list : {"frames", "figures"}) {
      for (const auto& f : next[list]) kept.insert(f["file"].get<std::string>());
    }
    for (const char* list : {"frames", "figures"}) {
      if (!manifest_.contains(list)) continue;
      for (const auto& f : manifest_[list]) {
        const std::string file = f["file"].get<std::string>();
        if (kept.count(file)) continue;
        VerifyItem item = make_item(list == std::string("frames") ? "frame" : "figure",
                                    fs::path(file).stem().string(), file);
        item.status = ItemStatus::removed;
        item.detail = "no longer part of the set";
        verdict.items.push_back(std::move(item));
      }
    }
  }

  void image_item(VerifyItem& item, const image::Image& actual, const fs::path& golden_file) {
    const bool have = fs::exists(golden_file);
    if (update_) {
      if (!have) {
        item.status = ItemStatus::added;
        item.detail = std::to_string(actual.width) + "x" + std::to_string(actual.height);
      } else {
        const image::CompareResult r =
            image::compare_images(image::read_png(golden_file), actual, options_);
        const bool same = !r.size_mismatch && r.max_channel_difference == 0;
        item.status = same ? ItemStatus::unchanged : ItemStatus::changed;
        item.detail = same ? "identical" : r.message;
      }
      // Every image of the new set goes to the stage, unchanged ones too (the same bytes).
      image::write_png(stage_ / golden_file.filename(), actual, image::PngSpeed::small);
      return;
    }
    if (!have) {
      item.status = ItemStatus::mismatch;
      item.detail = "no golden image " + golden_file.filename().string() + " (run verify --update)";
      write_evidence(item, actual, {});
      return;
    }
    const image::Image golden = image::read_png(golden_file);
    const image::CompareResult r = image::compare_images(golden, actual, options_);
    item.status = r.matches ? ItemStatus::match : ItemStatus::mismatch;
    item.detail = r.message;
    if (!r.matches) write_evidence(item, actual, golden_file);
  }

  // actual, golden and diff PNGs of a mismatch, in out/<scene>/.
  void write_evidence(VerifyItem& item, const image::Image& actual, const fs::path& golden_file) {
    make_real_directories(out_, job_.scene.name);  // never through a link (IoError)
    const std::string rel = job_.scene.name + "/" + item.name;
    image::write_png(out_ / (rel + ".actual.png"), actual, image::PngSpeed::small);
    item.actual = rel + ".actual.png";
    if (golden_file.empty() || !fs::exists(golden_file)) return;
    const image::Image golden = image::read_png(golden_file);
    image::write_png(out_ / (rel + ".golden.png"), golden, image::PngSpeed::small);
    item.golden = rel + ".golden.png";
    image::write_png(out_ / (rel + ".diff.png"),
                     image::diff_image(golden, actual, options_.channel_tolerance),
                     image::PngSpeed::small);
    item.diff = rel + ".diff.png";
  }

  VerifyJob& job_;
  fs::path golden_, stage_, out_;
  bool update_;
  json manifest_;
  image::CompareOptions options_;
};

}  // namespace

const char* status_name(ItemStatus s) {
  switch (s) {
    case ItemStatus::match:
      return "match";
    case ItemStatus::mismatch:
      return "MISMATCH";
    case ItemStatus::added:
      return "added";
    case ItemStatus::changed:
      return "changed";
    case ItemStatus::unchanged:
      return "unchanged";
    case ItemStatus::removed:
      return "removed";
  }
  return "?";
}

bool SceneVerdict::failed() const {
  if (!error.empty()) return true;
  return std::any_of(items.begin(), items.end(),
                     [](const VerifyItem& i) { return i.status == ItemStatus::mismatch; });
}

SceneVerdict verify_scene(VerifyJob& job, const fs::path& golden_root, const fs::path& out,
                          bool update) {
  const auto start = std::chrono::steady_clock::now();
  SceneVerdict verdict;
  try {
    const fs::path golden = golden_root / job.scene.name;
    if (update) {
      GoldenStage stage(golden);  // the old set stays as it is until commit()
      verdict = SceneVerifier(job, golden, out, update, stage.path()).run();
      stage.commit();
    } else {
      verdict = SceneVerifier(job, golden, out, update).run();
    }
  } catch (const std::exception& e) {
    verdict.scene = job.scene.name;
    verdict.error = e.what();
  }
  verdict.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return verdict;
}

}  // namespace stiction::services
