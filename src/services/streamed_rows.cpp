#include "services/streamed_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stiction::services {

std::size_t StreamedRows::video_stride(const core::RunOptions& run,
                                       const render::RenderSettings& render) {
  // Simulated seconds per video frame; the trail samples 96 points over trail_seconds
  // (render/scene_view.cpp, build_trail).
  double resolved = 1.0 / (render.fps * render.slow_motion);
  if (render.overlay.trail) resolved = std::min(resolved, render.overlay.trail_seconds / 96.0);
  const double rows = 0.5 * resolved * run.output_rate;
  if (!(rows >= 1.0)) return 1;
  return static_cast<std::size_t>(std::min(rows, 1e9));
}

StreamedRows::StreamedRows(const std::filesystem::path& csv,
                           const std::vector<std::string>& columns, const core::RunOptions& run,
                           const render::RenderSettings& render, bool plots, bool video)
    : csv_(csv, columns), plots_(columns, kPlotRows) {
  std::vector<core::RowSink*> sinks{&csv_};
  if (plots) sinks.push_back(&plots_);
  if (video) {
    // Never thinned beyond the stride: the video needs every row it samples.
    video_ = std::make_unique<core::DecimatedTrajectory>(
        columns, std::numeric_limits<std::size_t>::max() / 2, video_stride(run, render));
    sinks.push_back(video_.get());
  }
  fan_out_ = std::make_unique<core::RowFanOut>(std::move(sinks));
}

}  // namespace stiction::services
