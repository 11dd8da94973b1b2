#include "io/csv_writer.hpp"

#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/block_pipe.hpp"
#include "io/row_text.hpp"

namespace stiction::io {

void append_number(std::string& out, double v) {
  char buffer[kMaxNumberChars];
  out.append(buffer, format_number(buffer, v));
}

namespace {

std::string header(const std::vector<std::string>& columns) {
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) out += ',';
    out += columns[c];
  }
  out += '\n';
  return out;
}

constexpr std::size_t kFileChunk = std::size_t{1} << 20;

}  // namespace

void append_row(std::string& out, const double* row, std::size_t columns) {
  for (std::size_t c = 0; c < columns; ++c) {
    if (c > 0) out += ',';
    append_number(out, row[c]);
  }
  out += '\n';
}

CsvStream::CsvStream(const std::filesystem::path& path, const std::vector<std::string>& columns)
    : columns_(columns.size()),
      file_(std::make_unique<AtomicFile>(path)),
      text_(std::make_unique<TextBuffer>()),
      row_text_(std::make_unique<RowText>(columns.size())) {
  text_->reserve_more(kChunk + row_text_->max_row_chars());
  text_->append(header(columns));
  pipe_ = std::make_unique<BlockPipe>(
      columns_, [this](const double* rows, std::size_t count) { consume(rows, count); });
}

CsvStream::~CsvStream() { pipe_.reset(); }  // stops the writer before what it uses goes

void CsvStream::consume(const double* rows, std::size_t count) {
  for (std::size_t r = 0; r < count; ++r) {
    row_text_->append_row(*text_, rows + r * columns_);
    if (text_->size() >= kChunk) {
      file_->write(text_->view());
      text_->clear();
    }
  }
}

void CsvStream::write(const double* rows, std::size_t count, std::size_t columns) {
  if (columns != columns_) throw std::logic_error("CsvStream: rows of another width");
  pipe_->push(rows, count);
}

void CsvStream::commit() {
  pipe_->close();
  file_->write(text_->view());
  text_->clear();
  file_->commit();
}

double CsvStream::writer_cpu_seconds() const { return pipe_->writer_cpu_seconds(); }

std::string to_csv(const core::Trajectory& trajectory) {
  const std::size_t n = static_cast<std::size_t>(trajectory.column_count());
  TextBuffer text;
  text.append(header(trajectory.columns()));
  RowText rows(n);
  for (int r = 0; r < trajectory.row_count(); ++r) rows.append_row(text, trajectory.row(r));
  return std::string(text.view());
}

void write_csv(const core::Trajectory& trajectory, const std::filesystem::path& path) {
  AtomicFile file(path);
  // Rows go out in chunks: a long run need not hold its whole text in memory.
  const std::size_t n = static_cast<std::size_t>(trajectory.column_count());
  TextBuffer text;
  text.append(header(trajectory.columns()));
  RowText rows(n);
  for (int r = 0; r < trajectory.row_count(); ++r) {
    rows.append_row(text, trajectory.row(r));
    if (text.size() > kFileChunk) {
      file.write(text.view());
      text.clear();
    }
  }
  file.write(text.view());
  file.commit();
}

}  // namespace stiction::io
