// Where simulate() sends trajectory rows as it produces them, in blocks, so a run need not
// hold its whole trajectory in memory (issue 14, streaming): a CSV file on disk
// (io::CsvStream), a thinned copy for plots and video (DecimatedTrajectory), several at once
// (RowFanOut). Rows are [t, signal...] with Trajectory's columns.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/trajectory.hpp"

namespace stiction::core {

class RowSink {
 public:
  virtual ~RowSink() = default;
  // `count` rows of `columns` doubles each, row-major, in time order.
  virtual void write(const double* rows, std::size_t count, std::size_t columns) = 0;
  // After the last row (also after an instability).
  virtual void finish() {}
};

// Sends every block to each sink in turn.
class RowFanOut final : public RowSink {
 public:
  explicit RowFanOut(std::vector<RowSink*> sinks) : sinks_(std::move(sinks)) {}
  void write(const double* rows, std::size_t count, std::size_t columns) override {
    for (RowSink* s : sinks_) s->write(rows, count, columns);
  }
  void finish() override {
    for (RowSink* s : sinks_) s->finish();
  }

 private:
  std::vector<RowSink*> sinks_;
};

// Keeps a thinned trajectory of at most `capacity` rows whatever the run's length: every
// row while they fit, then every 2nd, 4th, ... row (each time the table fills, every other
// kept row is dropped and the stride doubles), plus always the first and the last row.
// With `min_stride`, only every min_stride-th row is considered at all (rows a reader does not
// need, e.g. the video's, which needs a few rows per frame). Memory: capacity rows.
class DecimatedTrajectory final : public RowSink {
 public:
  DecimatedTrajectory(std::vector<std::string> columns, std::size_t capacity,
                      std::size_t min_stride = 1);
  void write(const double* rows, std::size_t count, std::size_t columns) override;
  void finish() override;
  const Trajectory& trajectory() const { return trajectory_; }
  std::size_t rows_seen() const { return seen_; }
  std::size_t stride() const { return stride_; }

 private:
  void thin();
  Trajectory trajectory_;
  std::size_t capacity_;
  std::size_t stride_;
  std::size_t seen_ = 0;
  std::vector<double> last_;  // the last row seen, appended by finish() if not kept
  bool last_kept_ = false;
};

}  // namespace stiction::core
