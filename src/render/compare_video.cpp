#include "render/compare_video.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "render/frame_worker.hpp"
#include "render/number_format.hpp"
#include "render/overlay.hpp"
#include "render/scene_view.hpp"
#include "render/video_encoder.hpp"
#include "scene/scene.hpp"
#include "text/font.hpp"

namespace stiction::render {
namespace fs = std::filesystem;

namespace {

constexpr image::Rgba kGap{30, 32, 36, 255};  // between and around the tiles
constexpr int kGapPixels = 2;
constexpr image::Rgba kText{20, 22, 26, 255};

int even_below(double v) { return std::max(16, static_cast<int>(std::floor(v / 2.0)) * 2); }

// A translucent white panel with one line of text; `x`, `y`: its top left.
void label(image::Image& frame, text::Font& font, const text::TextStyle& style,
           const std::string& text, int x, int y) {
  const double pad = 0.5 * style.pixel_size;
  const double w = font.measure(text, style).width + 2.0 * pad;
  const double h = 1.35 * style.pixel_size + pad;
  for (int py = y; py < std::min(frame.height, int(std::ceil(y + h))); ++py) {
    for (int px = x; px < std::min(frame.width, int(std::ceil(x + w))); ++px) {
      frame.blend(px, py, {255, 255, 255, 255}, 0.9f);
    }
  }
  font.draw(frame, text, x + pad, y + 0.5 * pad + 1.0 * style.pixel_size, style);
}

// The time line with the overlay's speed note (none when the speed prints as 1/1).
std::string time_line(double t, double speed) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "t = %.3f s", t);
  return buffer + speed_note(speed);
}

}  // namespace

TileGrid::Box TileGrid::tile(int index) const {
  Box b;
  b.x0 = x0 + (index % columns) * (tile_width + kGapPixels);
  b.y0 = y0 + (index / columns) * (tile_height + kGapPixels);
  b.x1 = b.x0 + tile_width;
  b.y1 = b.y0 + tile_height;
  return b;
}

TileGrid tile_grid(int runs, int width, int height) {
  TileGrid g;
  g.columns = runs <= 2 ? std::max(runs, 1) : static_cast<int>(std::ceil(std::sqrt(double(runs))));
  g.rows = (std::max(runs, 1) + g.columns - 1) / g.columns;
  // A gap between tiles tells them apart; tiles have even sizes (the renderer's and the
  // encoder's habit) and the grid is centred in the frame.
  g.tile_width = even_below(double(width - kGapPixels * (g.columns - 1)) / g.columns);
  g.tile_height = even_below(double(height - kGapPixels * (g.rows - 1)) / g.rows);
  g.x0 = (width - (g.columns * g.tile_width + kGapPixels * (g.columns - 1))) / 2;
  g.y0 = (height - (g.rows * g.tile_height + kGapPixels * (g.rows - 1))) / 2;
  return g;
}

struct CompareFrames::Tile {
  std::string label;
  // The scene's [overlay] value, shown under the label (the time line is shared): a creeping
  // joint reads "1.234 mrad/s" beside one that holds at "0.000 rad/s".
  OverlaySettings overlay;
  double zero_below = -1.0;  // 1e-9 of the signal's largest magnitude, measured on first use
  double end = 0.0;
  std::unique_ptr<FrameRenderer> renderer;
  image::Image picture;
};

CompareFrames::CompareFrames(const std::vector<CompareRun>& runs) {
  if (runs.empty()) throw RenderError("compare --video: no runs");
  settings_ = runs.front().settings;
  settings_.slow_motion_around_events = 0.0;
  for (const CompareRun& r : runs) {
    settings_.slow_motion_around_events =
        std::max(settings_.slow_motion_around_events, r.settings.slow_motion_around_events);
    // The events each run's own video slows down around (slowed_events), all runs together.
    const std::vector<double> slowed =
        slowed_events(r.event_times, r.event_kinds, r.settings.slow_motion_around_events,
                      r.settings.slowed_events);
    events_.insert(events_.end(), slowed.begin(), slowed.end());
  }
  std::sort(events_.begin(), events_.end());
  grid_ = tile_grid(static_cast<int>(runs.size()), settings_.width, settings_.height);
  if (grid_.x0 < 0 || grid_.y0 < 0) {
    throw RenderError("compare --video: " + std::to_string(runs.size()) + " runs do not fit in " +
                      std::to_string(settings_.width) + "x" + std::to_string(settings_.height) +
                      " pixels (tiles of at least 16x16); give the first scene a larger [render] "
                      "size");
  }
  start_ = std::numeric_limits<double>::infinity();
  end_ = -start_;
  for (const CompareRun& r : runs) {
    RenderSettings s = r.settings;
    s.width = grid_.tile_width;
    s.height = grid_.tile_height;
    // One shared time line instead of one per tile, the run's label instead of the scene's
    // title and caption; forces, badges and the inset stay as the scene asks. Every tile is
    // exposed for the video's own frame interval (spin blur, forces averaged over it).
    s.overlay.panel = false;
    s.overlay.layers.title = "";
    s.overlay.layers.caption = "";
    s.fps = settings_.fps;
    s.slow_motion = settings_.slow_motion;
    auto tile = std::make_unique<Tile>();
    tile->label = r.label;
    if (r.settings.overlay.enabled) tile->overlay = r.settings.overlay;
    tile->renderer = frame_renderer_for(*r.scene, *r.trajectory, s, r.event_times, r.event_kinds);
    start_ = std::min(start_, tile->renderer->poses().start_time());
    tile->end = tile->renderer->poses().end_time();
    end_ = std::max(end_, tile->end);
    tiles_.push_back(std::move(tile));
  }
  // Each scene passed its own frame limit; the video runs over the longest at the first
  // scene's rate.
  if ((end_ - start_) * settings_.fps * settings_.slow_motion > kMaxFrames) {
    throw RenderError("compare --video: the runs span " + std::to_string(end_ - start_) +
                      " s, more than " + std::to_string(static_cast<long>(kMaxFrames)) +
                      " frames at the first scene's fps and slow_motion");
  }
  font_ = std::make_unique<text::Font>(text::Font::open_default());
}

CompareFrames::~CompareFrames() = default;

std::vector<FrameTime> CompareFrames::frame_times() const {
  const double step = 1.0 / (settings_.fps * settings_.slow_motion);
  return warped_frame_times(start_, end_, step, events_, settings_.slow_motion_around_events,
                            settings_.event_slow_motion);
}

void CompareFrames::render(double t, image::Image& out, double speed) {
  if (out.width != settings_.width || out.height != settings_.height) {
    out = image::Image(settings_.width, settings_.height, kGap);
  } else {
    out.fill(kGap);
  }
  text::TextStyle style;
  style.pixel_size = std::max(11.0, settings_.height / 30.0);
  style.colour = kText;
  for (std::size_t i = 0; i < tiles_.size(); ++i) {
    Tile& tile = *tiles_[i];
    // A run that ended holds its last picture (the renderer clamps t to its rows).
    tile.renderer->render(std::min(t, tile.end), tile.picture, speed);
    const TileGrid::Box box = grid_.tile(static_cast<int>(i));
    for (int y = 0; y < grid_.tile_height; ++y) {
      std::copy_n(tile.picture.data(0, y), static_cast<std::size_t>(grid_.tile_width) * 4,
                  out.data(box.x0, box.y0 + y));
    }
    const int pad = static_cast<int>(0.6 * style.pixel_size);
    label(out, *font_, style, tile.label, box.x0 + pad, box.y0 + pad);
    if (!tile.overlay.signal.empty()) {
      const PoseTrack& poses = tile.renderer->poses();
      // Zero below the run's stick threshold where the signal has one (as the video's
      // overlay prints it), else below 1e-9 of its largest magnitude (rounding noise).
      if (tile.zero_below < 0.0) tile.zero_below = tile.renderer->stuck_below(tile.overlay.signal);
      if (tile.zero_below < 0.0) {
        double largest = 0.0;
        for (int k = 0; k <= 512; ++k) {
          const double at =
              poses.start_time() + (poses.end_time() - poses.start_time()) * k / 512.0;
          const double v = std::abs(poses.signal(tile.overlay.signal, at));
          if (std::isfinite(v)) largest = std::max(largest, v);
        }
        tile.zero_below = 1e-9 * largest;
      }
      const Quantity q = format_quantity(poses.signal(tile.overlay.signal, std::min(t, tile.end)),
                                         tile.overlay.unit, tile.zero_below);
      std::string value = tile.overlay.label;
      value.append(" = ").append(q.number);
      if (!q.unit.empty()) value.append(" ").append(q.unit);
      label(out, *font_, style, value, box.x0 + pad,
            box.y0 + pad + static_cast<int>(1.5 * style.pixel_size + pad));
    }
  }
  // The shared time line: centred at the bottom, or in the grid's empty cell when there is
  // one (3 runs in 2 x 2), where it covers no run.
  const std::string line = time_line(t, speed);
  const double w = font_->measure(line, style).width + style.pixel_size;
  int x = static_cast<int>((settings_.width - w) / 2.0);
  int y = settings_.height - static_cast<int>(2.2 * style.pixel_size);
  const int runs = static_cast<int>(tiles_.size());
  if (grid_.columns * grid_.rows > runs) {
    const TileGrid::Box empty = grid_.tile(grid_.columns * grid_.rows - 1);
    x = static_cast<int>((empty.x0 + empty.x1 - w) / 2.0);
    y = static_cast<int>((empty.y0 + empty.y1) / 2.0 - style.pixel_size);
  }
  label(out, *font_, style, line, std::max(0, x), std::max(0, y));
}

image::Image CompareFrames::render(double t, double speed) {
  image::Image out;
  render(t, out, speed);
  return out;
}

RenderResult render_compare_video(const std::vector<CompareRun>& runs,
                                  const CompareVideoRequest& request) {
  const auto started = std::chrono::steady_clock::now();
  RenderResult result;
  CompareFrames frames(runs);
  const std::vector<FrameTime> times = frames.frame_times();
  std::error_code ec;
  fs::create_directories(request.out_dir, ec);
  if (ec) throw VideoError("cannot create " + request.out_dir.string() + ": " + ec.message());
  const RenderSettings& settings = frames.settings();
  VideoEncoder encoder(request.out_dir / "compare.mp4", video_options(settings));
  render_frame_sequence(
      times, [&](const FrameTime& f, image::Image& frame) { frames.render(f.t, frame, f.speed); },
      &encoder, std::nullopt, request.cancel, request.progress, started, result);
  result.video = encoder.finish(result.interrupted ? request.out_dir / "compare.partial.mp4"
                                                   : request.out_dir / "compare.mp4");
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace stiction::render
