#include "io/csv_writer.hpp"

#include <algorithm>
#include <charconv>

#include "io/atomic_file.hpp"

namespace stiction::io {

void append_number(std::string& out, double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, result.ptr);
  // "0" or "12" would read back as integers (pandas makes such a column int64): a number
  // without a point, exponent or letter (nan, inf) gets ".0" (DESIGN section 4).
  if (std::find_if(buffer, result.ptr, [](char c) { return c != '-' && (c < '0' || c > '9'); }) ==
      result.ptr) {
    out += ".0";
  }
}

void append_row(std::string& out, const double* row, std::size_t columns);

namespace {

void append_header(std::string& out, const core::Trajectory& trajectory) {
  const auto& columns = trajectory.columns();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) out += ',';
    out += columns[c];
  }
  out += '\n';
}

void append_trajectory_row(std::string& out, const core::Trajectory& trajectory, int r) {
  io::append_row(out, trajectory.row(r), static_cast<std::size_t>(trajectory.column_count()));
}

constexpr std::size_t kChunk = 1u << 20;

}  // namespace

void append_row(std::string& out, const double* row, std::size_t columns) {
  for (std::size_t c = 0; c < columns; ++c) {
    if (c > 0) out += ',';
    append_number(out, row[c]);
  }
  out += '\n';
}

CsvStream::CsvStream(const std::filesystem::path& path, const std::vector<std::string>& columns)
    : file_(std::make_unique<AtomicFile>(path)) {
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) buffer_ += ',';
    buffer_ += columns[c];
  }
  buffer_ += '\n';
}

CsvStream::~CsvStream() = default;

void CsvStream::write(const double* rows, std::size_t count, std::size_t columns) {
  for (std::size_t r = 0; r < count; ++r) append_row(buffer_, rows + r * columns, columns);
  if (buffer_.size() > kChunk) {
    file_->write(buffer_);
    buffer_.clear();
  }
}

void CsvStream::commit() {
  file_->write(buffer_);
  buffer_.clear();
  buffer_.shrink_to_fit();
  file_->commit();
}

std::string to_csv(const core::Trajectory& trajectory) {
  std::string out;
  append_header(out, trajectory);
  for (int r = 0; r < trajectory.row_count(); ++r) append_trajectory_row(out, trajectory, r);
  return out;
}

void write_csv(const core::Trajectory& trajectory, const std::filesystem::path& path) {
  AtomicFile file(path);
  // Rows go out in chunks: a long run need not hold its whole text in memory.
  std::string chunk;
  append_header(chunk, trajectory);
  for (int r = 0; r < trajectory.row_count(); ++r) {
    append_trajectory_row(chunk, trajectory, r);
    if (chunk.size() > kChunk) {
      file.write(chunk);
      chunk.clear();
    }
  }
  file.write(chunk);
  file.commit();
}

}  // namespace stiction::io
