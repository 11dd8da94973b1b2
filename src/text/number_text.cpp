#include "text/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdio>

namespace stiction::text {

std::string shortest(double value) {
  char buffer[64];
  const auto [end, error] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific);
  if (error != std::errc{}) return "nan";  // cannot happen for a 64-byte buffer
  if (!std::isfinite(value)) return std::string(buffer, end);
  // The shortest digits, in printf's %g notation (0.0001 and 20, not to_chars' 1e-04 and
  // 2e+01): as many significant digits as the shortest form has (more for the integer part
  // of a number below 1e16), which reads back as the same value.
  const std::string text(buffer, end);
  const std::size_t e = text.find('e');
  const int exponent = std::atoi(text.c_str() + e + 1);
  int digits = 0;
  for (std::size_t i = 0; i < e; ++i) digits += text[i] >= '0' && text[i] <= '9' ? 1 : 0;
  if (exponent >= 0 && exponent < 16) digits = std::max(digits, exponent + 1);
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
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
