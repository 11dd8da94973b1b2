#include "render/number_format.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace stiction::render {
namespace {

struct Prefix {
  int exponent;
  const char* symbol;
};
// "u" rather than the micro sign: the overlay's font has it, but log files and terminals
// that show the same strings may not.
constexpr std::array<Prefix, 9> kPrefixes{{{-15, "f"},
                                           {-12, "p"},
                                           {-9, "n"},
                                           {-6, "u"},
                                           {-3, "m"},
                                           {0, ""},
                                           {3, "k"},
                                           {6, "M"},
                                           {9, "G"}}};

std::string fixed(double v, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

// Four significant digits of a value in [1, 1000): 1.234, 12.34, 123.4.
std::string four_digits(double scaled) {
  const double a = std::abs(scaled);
  return fixed(scaled, a < 9.9995 ? 3 : (a < 99.995 ? 2 : 1));
}

}  // namespace

bool takes_si_prefix(const std::string& unit) {
  static const std::array<const char*, 10> symbols{"rad", "Pa", "Hz", "m", "s",
                                                   "N",   "J",  "W",  "A", "V"};
  for (const char* s : symbols) {
    const std::string sym(s);
    if (unit.compare(0, sym.size(), sym) != 0) continue;
    // The symbol must end there: "m/s" and "N m" yes, "min" or "mol" no.
    if (unit.size() == sym.size()) return true;
    const char next = unit[sym.size()];
    return next == '/' || next == ' ' || next == '^' || next == '*' || next == '.' ||
           (next >= '0' && next <= '9') || static_cast<unsigned char>(next) >= 0x80;
  }
  return false;
}

Quantity format_quantity(double value, const std::string& unit, double zero_below) {
  if (std::isnan(value)) return {"n/a", unit};
  if (std::isinf(value)) return {value > 0 ? "inf" : "-inf", unit};
  if (std::abs(value) < zero_below) value = 0.0;
  const double a = std::abs(value);
  if (takes_si_prefix(unit)) {
    if (a < 1e-15) return {four_digits(0.0), unit};
    // The prefix that puts the value in [1, 1000), after rounding to four digits.
    const Prefix* chosen = &kPrefixes.front();
    for (const Prefix& p : kPrefixes) {
      if (a >= std::pow(10.0, p.exponent) * (1.0 - 5e-5)) chosen = &p;
    }
    double scaled = value / std::pow(10.0, chosen->exponent);
    if (std::abs(scaled) >= 999.95 && chosen != &kPrefixes.back()) {
      ++chosen;
      scaled = value / std::pow(10.0, chosen->exponent);
    }
    return {four_digits(scaled), std::string(chosen->symbol) + unit};
  }
  if (a == 0.0 || (a >= 0.00999995 && a < 9999.5)) {
    const int digits = a == 0.0 ? 0 : static_cast<int>(std::floor(std::log10(a)));
    return {fixed(value, std::max(0, 3 - digits)), unit};
  }
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.3e", value);
  return {buffer, unit};
}

std::vector<std::string> possible_units(const std::string& unit) {
  if (!takes_si_prefix(unit)) return {unit};
  std::vector<std::string> out;
  for (const Prefix& p : kPrefixes) out.push_back(std::string(p.symbol) + unit);
  return out;
}

std::vector<std::string> widest_number_candidates(const std::string& unit) {
  // Templates of every shape the formatter produces; '#' stands for any digit.
  std::vector<std::string> shapes{"-###.#", "-##.##", "-#.###"};
  if (!takes_si_prefix(unit)) {
    shapes = {"-####",   "-###.#",  "-##.##",     "-#.###",     "-0.0####",    "-##.###",
              "-###.##", "-####.#", "-#.###e-##", "-#.###e+##", "-#.###e-###", "-#.###e+###"};
  }
  std::vector<std::string> out;
  for (const std::string& shape : shapes) {
    for (char d = '0'; d <= '9'; ++d) {
      std::string s = shape;
      for (char& c : s) {
        if (c == '#') c = d;
      }
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace stiction::render
