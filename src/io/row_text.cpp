#include "io/row_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace stiction::io {

char* format_number(char* out, double v) {
  if (v == 0.0) {  // both zeros, the commonest value of all
    if (std::signbit(v)) *out++ = '-';
    std::memcpy(out, "0.0", 3);
    return out + 3;
  }
  const auto result = std::to_chars(out, out + kMaxNumberChars, v);
  char* end = result.ptr;
  // "0" or "12" would read back as integers (pandas makes such a column int64): a number
  // without a point, exponent or letter (nan, inf) gets ".0" (DESIGN section 4). Such a text
  // is at most 22 digits and a sign (a longer whole number is written with an exponent), so
  // the two characters fit in kMaxNumberChars.
  if (std::find_if(out, end, [](char c) { return c != '-' && (c < '0' || c > '9'); }) == end) {
    end[0] = '.';
    end[1] = '0';
    end += 2;
  }
  return end;
}

char* TextBuffer::reserve_more(std::size_t n) {
  if (size_ + n > capacity_) {
    const std::size_t capacity = std::max(size_ + n, 2 * capacity_);
    std::unique_ptr<char[]> grown(new char[capacity]);
    if (size_ > 0) std::memcpy(grown.get(), data_.get(), size_);
    data_ = std::move(grown);
    capacity_ = capacity;
  }
  return end();
}

void TextBuffer::append(std::string_view text) {
  char* at = reserve_more(text.size());
  if (!text.empty()) std::memcpy(at, text.data(), text.size());
  size_ += text.size();
}

RowText::RowText(std::size_t columns) : cells_(columns) {}

char* RowText::write_row(char* out, const double* row) {
  const std::size_t n = cells_.size();
  for (std::size_t c = 0; c < n; ++c) {
    Cell& cell = cells_[c];
    std::uint64_t bits;
    std::memcpy(&bits, &row[c], sizeof bits);
    if (!cell.valid || bits != cell.bits) {
      char* end = format_number(cell.text, row[c]);
      cell.size = static_cast<unsigned char>(end - cell.text);
      cell.bits = bits;
      cell.valid = true;
      ++converted_;
    }
    // The whole padded cell in one fixed-size move; the next cell overwrites the excess.
    std::memcpy(out, cell.text, sizeof cell.text);
    out += cell.size;
    *out++ = ',';
  }
  if (n > 0) --out;
  *out++ = '\n';
  return out;
}

void RowText::append_row(TextBuffer& out, const double* row) {
  char* at = out.reserve_more(max_row_chars());
  out.set_end(write_row(at, row));
}

}  // namespace stiction::io
