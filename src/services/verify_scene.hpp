// One scene of `stiction verify`: simulate, render the chosen frames and the figures, take
// the key numbers of summary.json, and compare them with the golden set DIR/<scene>/ (or
// write it, with --update).
//
// A golden set holds golden.json (frame times and files, figure files, the key numbers) and
// the PNGs it names: frame_NNN.png, figure_NAME.png. Frames are paired by index and must
// show the same time; a scene verified without --at or [verify] at renders the golden's own
// frame times, so an event that moves changes the numbers, not which frames are compared.
//
// Images match when at most `max_differing` of the pixels differ by more than
// `pixel_tolerance` in some channel and the RMS channel difference is at most `max_rms`;
// numbers when |actual - golden| <= abs_tolerance + rel_tolerance |golden|; text exactly.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "services/verify_settings.hpp"
#include "plot/plot_spec.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

// Everything read (and checked) before any scene is simulated.
struct VerifyJob {
  scene::Scene scene;
  render::RenderSettings render;
  std::vector<plot::PlotSpec> plots;
  VerifySettings settings;
  std::vector<double> at;  // from --at; empty: [verify] at, the golden's, or the default
};

enum class ItemStatus { match, mismatch, added, changed, unchanged, removed };
const char* status_name(ItemStatus s);

struct VerifyItem {
  std::string kind;  // "frame", "figure", "numbers"
  std::string name;  // "frame_001", "figure_motion", "numbers"
  std::string what;  // "frame at t = 0.375 s", "figure motion", "key numbers"
  ItemStatus status = ItemStatus::match;
  std::string detail;                    // one line: the metric, or the count of differences
  std::vector<std::string> differences;  // numbers: one line per differing key
  // Written for a mismatch, relative to the report directory (empty when not written).
  std::string actual, golden, diff;
};

struct SceneVerdict {
  std::string scene;
  std::vector<VerifyItem> items;
  std::string error;  // a failure that is not a difference (rendering, I/O): exit 1
  double seconds = 0.0;
  bool failed() const;
};

// `out` is the report directory; images of mismatches go to out/<scene>/.
SceneVerdict verify_scene(VerifyJob& job, const std::filesystem::path& golden_root,
                          const std::filesystem::path& out, bool update);

}  // namespace stiction::services
