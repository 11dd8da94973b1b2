// A double as TOML text for generated scenes: every digit kept, and always a float literal
// ("1.0", not "1", which TOML reads as an integer).
#pragma once

#include <cstdio>
#include <string>

namespace stiction::testing {

inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace stiction::testing
