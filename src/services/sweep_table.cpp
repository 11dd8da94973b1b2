#include "services/sweep_table.hpp"

#include <charconv>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"

namespace stiction::services {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line += csv_field(fields[i]);
  }
  return line;
}

bool parse_csv_line(const std::string& line, std::vector<std::string>& fields) {
  fields.clear();
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"' && field.empty()) {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
    } else {
      field += c;
    }
  }
  if (quoted) return false;
  fields.push_back(std::move(field));
  return true;
}

SweepTable read_sweep_table(const std::filesystem::path& path) {
  SweepTable table;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return table;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::IoError(path.string() + ": cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::size_t start = 0;
  bool first = true;
  std::vector<std::string> fields;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // no newline: a row cut short
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    if (!parse_csv_line(line, fields)) continue;
    if (first) {
      table.header = fields;
      first = false;
      continue;
    }
    if (fields.size() != table.header.size()) continue;
    std::size_t index = 0;
    const auto [ptr, err] =
        std::from_chars(fields[0].data(), fields[0].data() + fields[0].size(), index);
    if (err != std::errc() || ptr != fields[0].data() + fields[0].size()) continue;
    if (table.rows.count(index) > 0) table.repeated.push_back(index);
    table.rows[index] = fields;
  }
  return table;
}

void write_sweep_table(const SweepTable& table, const std::filesystem::path& path) {
  std::string text = csv_line(table.header) + "\n";
  for (const auto& [index, fields] : table.rows) text += csv_line(fields) + "\n";
  io::write_file_atomically(path, text);
}

SweepAppender::SweepAppender(const std::filesystem::path& path,
                             const std::vector<std::string>& header)
    : path_(path) {
  std::error_code ec;
  const bool fresh =
      !std::filesystem::exists(path, ec) || std::filesystem::file_size(path, ec) == 0;
  file_ = std::fopen(path.c_str(), "ab");
  if (file_ == nullptr) throw io::IoError(path.string() + ": cannot open for writing");
  if (fresh) {
    const std::string line = csv_line(header) + "\n";
    std::fwrite(line.data(), 1, line.size(), file_);
    std::fflush(file_);
  }
}

SweepAppender::~SweepAppender() {
  if (file_ != nullptr) std::fclose(file_);
}

void SweepAppender::append(const std::vector<std::string>& fields) {
  const std::string line = csv_line(fields) + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0) {
    throw io::IoError(path_.string() + ": write failed");
  }
}

}  // namespace stiction::services
