// Where `run` sends its rows while simulating (issue 14, streaming): trajectory.csv on disk as
// they come, a copy for the plots thinned to at most kPlotRows rows (a 2 s run at 1 kHz keeps
// every row; a 1000 s one every 64th), and for the video only the rows it samples: a few per
// frame and per step of the overlay's trail. Peak memory is then bounded by the plot copy
// and, with a video, by the length of the video, not by the number of rows.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/row_sink.hpp"
#include "core/simulation.hpp"
#include "io/csv_writer.hpp"
#include "render/render_settings.hpp"

namespace stiction::services {

class StreamedRows {
 public:
  static constexpr std::size_t kPlotRows = 16384;

  StreamedRows(const std::filesystem::path& csv, const std::vector<std::string>& columns,
               const core::RunOptions& run, const render::RenderSettings& render, bool plots,
               bool video);
  core::RowSink& sink() { return *fan_out_; }
  void commit_csv() { csv_.commit(); }
  // CPU seconds trajectory.csv's writer thread spent (after commit_csv()).
  double csv_writer_cpu_seconds() const { return csv_.writer_cpu_seconds(); }
  const core::Trajectory& for_plots() const { return plots_.trajectory(); }
  const core::Trajectory& for_video() const { return video_->trajectory(); }

  // Every how many rows the video needs one: half the smallest time it resolves (a frame,
  // or a step of the trail it draws) in rows at the output rate; at least 1.
  static std::size_t video_stride(const core::RunOptions& run,
                                  const render::RenderSettings& render);

 private:
  io::CsvStream csv_;
  core::DecimatedTrajectory plots_;
  std::unique_ptr<core::DecimatedTrajectory> video_;
  std::unique_ptr<core::RowFanOut> fan_out_;
};

}  // namespace stiction::services
