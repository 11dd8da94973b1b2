// The text of trajectory.csv's numbers (DESIGN section 4), made cheaply: the shortest
// representation that reads back to the same double (std::to_chars), always as a float
// ("0.0", "12.0", "1e+20", "nan", "inf"). RowText formats whole rows and copies a cell's
// previous text when its value has not changed (bit for bit) since the row before: columns
// that hold still (a body at rest, a contact that is open, a quaternion's unused parts) cost
// a copy instead of a conversion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

namespace stiction::io {

// The longest text format_number writes: to_chars prefers the fixed form at equal length,
// so -2139563737866039721984 (23 characters, as long as -2.1395637378660397e+21) gets its
// ".0" and takes 25; "-2.2250738585072014e-308" takes 24.
inline constexpr std::size_t kMaxNumberChars = 25;

// Writes v's text at `out` (room for kMaxNumberChars) and returns the end of what it wrote.
char* format_number(char* out, double v);

// A growable block of text without the zero-filling of std::string::resize.
class TextBuffer {
 public:
  // Room for at least `n` more characters after end(); end() may move.
  char* reserve_more(std::size_t n);
  char* end() { return data_.get() + size_; }
  void set_end(char* end) { size_ = static_cast<std::size_t>(end - data_.get()); }
  void append(std::string_view text);
  std::string_view view() const { return {data_.get(), size_}; }
  std::size_t size() const { return size_; }
  void clear() { size_ = 0; }

 private:
  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

// Rows of a fixed number of columns, in order; each row is its cells joined by ',' and
// ended by '\n', byte for byte what format_number gives cell by cell.
class RowText {
 public:
  explicit RowText(std::size_t columns);
  std::size_t columns() const { return cells_.size(); }
  // The room write_row needs: the longest row, and a cell's padding (it copies each cell's
  // text in one fixed-size move, which may reach past the row's end).
  std::size_t max_row_chars() const { return cells_.size() * (kMaxNumberChars + 1) + 1 + kPad; }
  // Writes the row at `out` (room for max_row_chars()) and returns the end.
  char* write_row(char* out, const double* row);
  void append_row(TextBuffer& out, const double* row);
  // Cells formatted anew (not copied from the row before), for tests and measurements.
  std::uint64_t converted() const { return converted_; }

 private:
  static constexpr std::size_t kPad = kMaxNumberChars + 8;
  struct Cell {
    std::uint64_t bits = 0;
    bool valid = false;
    unsigned char size = 0;
    char text[kPad] = {};  // padded: copied whole, in one fixed-size move
  };
  std::vector<Cell> cells_;
  std::uint64_t converted_ = 0;
};

}  // namespace stiction::io
