// sweep.csv and its shards (docs/sweeps.md): a header row, then one row per point sorted by
// the `point` column (its index in the sweep). Fields are quoted as RFC 4180 says when they
// hold a comma, a quote or a line break; numbers are the shortest text that reads back to
// the same double. Rows are appended as points finish (so an interrupted sweep keeps them)
// and the file is rewritten sorted at the end.
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace stiction::services {

std::string csv_field(const std::string& text);
std::string csv_line(const std::vector<std::string>& fields);
// Splits one line (without its newline); false when the quoting is broken.
bool parse_csv_line(const std::string& line, std::vector<std::string>& fields);

struct SweepTable {
  std::vector<std::string> header;
  std::map<std::size_t, std::vector<std::string>> rows;  // by point index
  std::vector<std::size_t> repeated;  // indices read more than once (the last row is kept)
};

// Reads a table. Lines that are incomplete (no final newline: an interrupted write) or whose
// field count differs from the header's are dropped. An absent file gives an empty table.
// io::IoError when the file exists but cannot be read.
SweepTable read_sweep_table(const std::filesystem::path& path);

// Header and rows sorted by point, written atomically.
void write_sweep_table(const SweepTable& table, const std::filesystem::path& path);

// Appends rows to a table file as they come, flushing each: an interrupted sweep keeps every
// finished row. Creates the file with the header when it does not exist.
class SweepAppender {
 public:
  SweepAppender(const std::filesystem::path& path, const std::vector<std::string>& header);
  ~SweepAppender();
  SweepAppender(const SweepAppender&) = delete;
  SweepAppender& operator=(const SweepAppender&) = delete;
  void append(const std::vector<std::string>& fields);

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

}  // namespace stiction::services
