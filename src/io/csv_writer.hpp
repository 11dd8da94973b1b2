// trajectory.csv (DESIGN section 4): a header row of column names, then one row per sample.
// Numbers are written as the shortest text that reads back to the same double
// (std::to_chars), so the file is exact and compact; whole numbers get ".0" so that every
// column reads as floats; non-finite values read nan / inf.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/row_sink.hpp"
#include "core/trajectory.hpp"

namespace stiction::io {

// Appends the shortest round-trip representation of v, always as a float: 0 -> "0.0",
// 12 -> "12.0", 1e+20 stays "1e+20".
void append_number(std::string& out, double v);

std::string to_csv(const core::Trajectory& trajectory);
// Written atomically; IoError on failure.
void write_csv(const core::Trajectory& trajectory, const std::filesystem::path& path);

// One row as write_csv writes it (with its newline).
void append_row(std::string& out, const double* row, std::size_t columns);

class AtomicFile;

// trajectory.csv written as simulate() produces the rows (core::RowSink): the same bytes as
// write_csv, through a text buffer of about 1 MiB, into a temporary file that commit()
// renames onto `path` (io::AtomicFile). IoError on failure.
class CsvStream final : public core::RowSink {
 public:
  CsvStream(const std::filesystem::path& path, const std::vector<std::string>& columns);
  ~CsvStream() override;
  void write(const double* rows, std::size_t count, std::size_t columns) override;
  void commit();

 private:
  std::unique_ptr<AtomicFile> file_;
  std::string buffer_;
};

}  // namespace stiction::io
