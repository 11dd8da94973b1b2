// Command-line number checks. CLI::PositiveNumber lets "nan" through (nan <= 0 is false) and
// accepts "inf"; every number read from the command line must be finite as well.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>

namespace stiction::app {

inline CLI::Validator finite_positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return "expected a number, got '" + text + "'";
        if (!std::isfinite(v)) return "expected a finite number, got '" + text + "'";
        if (!(v > 0.0)) return "expected a number > 0, got '" + text + "'";
        return {};
      },
      "FINITE > 0");
}

}  // namespace stiction::app
