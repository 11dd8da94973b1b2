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

namespace {

void append_header(std::string& out, const core::Trajectory& trajectory) {
  const auto& columns = trajectory.columns();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) out += ',';
    out += columns[c];
  }
  out += '\n';
}

void append_row(std::string& out, const core::Trajectory& trajectory, int r) {
  const double* row = trajectory.row(r);
  for (int c = 0; c < trajectory.column_count(); ++c) {
    if (c > 0) out += ',';
    append_number(out, row[c]);
  }
  out += '\n';
}

}  // namespace

std::string to_csv(const core::Trajectory& trajectory) {
  std::string out;
  append_header(out, trajectory);
  for (int r = 0; r < trajectory.row_count(); ++r) append_row(out, trajectory, r);
  return out;
}

void write_csv(const core::Trajectory& trajectory, const std::filesystem::path& path) {
  AtomicFile file(path);
  // Rows go out in chunks: a long run need not hold its whole text in memory.
  std::string chunk;
  append_header(chunk, trajectory);
  for (int r = 0; r < trajectory.row_count(); ++r) {
    append_row(chunk, trajectory, r);
    if (chunk.size() > (1u << 20)) {
      file.write(chunk);
      chunk.clear();
    }
  }
  file.write(chunk);
  file.commit();
}

}  // namespace stiction::io
