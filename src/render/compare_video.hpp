// `stiction compare A B ... --video`: one video, OUT/compare.mp4, of the runs side by side
// (2 runs: left and right; more: a grid of ceil(sqrt(n)) columns), synchronized on simulated
// time, each tile labelled with its run's label at its top left and, under it, its scene's
// [overlay] value ("joint 1 speed = 0.000 rad/s"); one time line for all at the bottom (or in
// the grid's empty cell). Each tile is drawn by a FrameRenderer of its own run (its scene's
// camera, trail and inset; its time overlay is off: the shared time line replaces it) at the
// tile's size, and the tiles are copied into one frame that the FrameWorker encodes, as
// render_outputs does. The frame is the first run's [render] size, fps, crf and preset; the
// video slows down around the union of every run's events when any scene sets
// slow_motion_around_events (the largest window and the first run's event_slow_motion). A run that
// ends before the others holds its last picture.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "image/image.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "render/time_warp.hpp"

namespace stiction::scene {
struct Scene;
}
namespace stiction::text {
class Font;
}

namespace stiction::render {

// One run of the comparison.
struct CompareRun {
  std::string label;
  const scene::Scene* scene = nullptr;
  const core::Trajectory* trajectory = nullptr;
  RenderSettings settings;               // read from its scene (read_render_settings)
  std::vector<double> event_times;       // its stick/slip events
  std::vector<std::string> event_kinds;  // parallel to event_times; may be empty
};

struct CompareVideoRequest {
  std::filesystem::path out_dir;  // writes OUT/compare.mp4
  std::function<void(const RenderProgress&)> progress;
  const std::atomic<bool>* cancel = nullptr;  // Ctrl-C: OUT/compare.partial.mp4
};

// Where the tiles go in a width x height frame: `columns` x `rows` tiles of tile_width x
// tile_height (even numbers), tile i at column i % columns, row i / columns, the grid centred.
struct TileGrid {
  int columns = 1, rows = 1;
  int tile_width = 0, tile_height = 0;
  int x0 = 0, y0 = 0;  // top left of the grid
  struct Box {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  };
  Box tile(int index) const;
};
TileGrid tile_grid(int runs, int width, int height);

// The frames of a comparison, one at a time (the video, the tests, the golden image).
class CompareFrames {
 public:
  explicit CompareFrames(const std::vector<CompareRun>& runs);
  ~CompareFrames();
  CompareFrames(const CompareFrames&) = delete;
  CompareFrames& operator=(const CompareFrames&) = delete;

  // The video's frame times: from the earliest start to the latest end of the runs, warped
  // around the union of their events.
  std::vector<FrameTime> frame_times() const;
  const RenderSettings& settings() const { return settings_; }
  const TileGrid& grid() const { return grid_; }

  void render(double t, image::Image& out, double speed = 1.0);
  image::Image render(double t, double speed = 1.0);

 private:
  struct Tile;
  RenderSettings settings_;  // the video's (first run's, with the slow motion of all)
  TileGrid grid_;
  std::vector<double> events_;
  double start_ = 0.0, end_ = 0.0;
  std::vector<std::unique_ptr<Tile>> tiles_;
  std::unique_ptr<text::Font> font_;
};

RenderResult render_compare_video(const std::vector<CompareRun>& runs,
                                  const CompareVideoRequest& request);

}  // namespace stiction::render
