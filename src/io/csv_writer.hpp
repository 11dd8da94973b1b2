// trajectory.csv (DESIGN section 4): a header row of column names, then one row per sample.
// Numbers are written as the shortest text that reads back to the same double
// (std::to_chars), so the file is exact and compact; whole numbers get ".0" so that every
// column reads as floats; non-finite values read nan / inf (io/row_text.hpp makes the text).
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
class BlockPipe;
class RowText;
class TextBuffer;

// trajectory.csv written as simulate() produces the rows (core::RowSink): the same bytes as
// write_csv, into a temporary file that commit() renames onto `path` (io::AtomicFile).
// write() only copies the rows into a ring of blocks (io::BlockPipe); a writer thread
// formats them (io::RowText) and writes the text in chunks of kChunk bytes. IoError on
// failure: a failed write on the writer thread is thrown by the next write() or by commit().
// Destroyed without commit() (an error, an interrupt the caller does not keep), it stops the
// writer and leaves no file under `path`.
class CsvStream final : public core::RowSink {
 public:
  static constexpr std::size_t kChunk = std::size_t{1} << 18;

  CsvStream(const std::filesystem::path& path, const std::vector<std::string>& columns);
  ~CsvStream() override;
  void write(const double* rows, std::size_t count, std::size_t columns) override;
  // Waits for the writer, writes the rest and renames the file into place.
  void commit();
  // CPU seconds the writer thread spent formatting and writing (after commit()).
  double writer_cpu_seconds() const;

 private:
  void consume(const double* rows, std::size_t count);  // on the writer thread

  std::size_t columns_;
  std::unique_ptr<AtomicFile> file_;
  std::unique_ptr<TextBuffer> text_;
  std::unique_ptr<RowText> row_text_;
  std::unique_ptr<BlockPipe> pipe_;  // last: its thread uses the members above
};

}  // namespace stiction::io
