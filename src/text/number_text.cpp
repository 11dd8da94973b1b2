#include "text/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace stiction::text {

std::string shortest(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (error != std::errc{}) return "nan";  // cannot happen for a 64-byte buffer
  return std::string(buffer, end);
}

std::string significant(double value, int digits) {
  digits = std::clamp(digits, 1, 17);
  char buffer[64];
  // %g already drops trailing zeros and the point; it is the stated rule, with C's spelling of
  // non-finite values.
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace stiction::text
