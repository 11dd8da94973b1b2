#include "plot/ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

namespace stiction::plot {
namespace {

// 10^n exactly for |n| <= 22 (integers below 2^53), by std::pow otherwise.
double power_of_ten(int n) {
  double result = 1.0;
  if (n >= 0 && n <= 22) {
    for (int i = 0; i < n; ++i) result *= 10.0;
    return result;
  }
  return std::pow(10.0, n);
}

// m * 10^k * i, computed with one rounding when 10^-k is exact.
double tick_value(long i, int m, int k) {
  if (k < 0 && -k <= 22) return static_cast<double>(i * m) / power_of_ten(-k);
  return static_cast<double>(i * m) * power_of_ten(k);
}

constexpr double kHuge = 1e300;

}  // namespace

Range finite_range(const std::vector<double>& data) {
  Range r{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  for (double v : data) {
    if (!std::isfinite(v)) continue;
    if (!(r.min <= v)) r.min = v;
    if (!(r.max >= v)) r.max = v;
  }
  return r;
}

Range positive_range(const std::vector<double>& data) {
  Range r{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  for (double v : data) {
    if (!std::isfinite(v) || v <= 0.0) continue;
    if (!(r.min <= v)) r.min = v;
    if (!(r.max >= v)) r.max = v;
  }
  return r;
}

Ticks nice_ticks(double min, double max, int target_count) {
  const int target = std::max(target_count, 2);
  const bool min_ok = std::isfinite(min);
  const bool max_ok = std::isfinite(max);
  if (!min_ok && !max_ok) {
    min = 0.0;
    max = 1.0;
  } else if (!min_ok) {
    min = max;
  } else if (!max_ok) {
    max = min;
  }
  if (min > max) std::swap(min, max);
  min = std::clamp(min, -kHuge, kHuge);
  max = std::clamp(max, -kHuge, kHuge);

  const double magnitude = std::max(std::abs(min), std::abs(max));
  if (max - min <= magnitude * 1e-12) {
    // Flat: a range of +-10% around the value, or [-1, 1] around zero.
    const double centre = 0.5 * (min + max);
    const double half = std::abs(centre) > 1e-290 ? std::abs(centre) * 0.1 : 1.0;
    min = centre - half;
    max = centre + half;
  }
  const double span = max - min;

  const int k0 = static_cast<int>(std::floor(std::log10(span / (target - 1))));
  Ticks best;
  int best_score = std::numeric_limits<int>::max();
  int best_m = 1, best_k = 0;
  long best_lo = 0, best_hi = 1;
  for (int k = k0 - 1; k <= k0 + 1; ++k) {
    for (int m : {1, 2, 5}) {
      const double step = m * power_of_ten(k);
      const long lo = static_cast<long>(std::floor(min / step + 1e-9));
      const long hi = static_cast<long>(std::ceil(max / step - 1e-9));
      // Judge by the ticks inside [min, max]: those are the ones a padded axis shows.
      const long inside = static_cast<long>(std::floor(max / step + 1e-9)) -
                          static_cast<long>(std::ceil(min / step - 1e-9)) + 1;
      const int score = static_cast<int>(std::min<long>(std::labs(inside - target), 1000000)) +
                        (inside < 2 ? 1000 : 0);
      if (score <= best_score) {  // steps grow through the loop: ties take the larger
        best_score = score;
        best_m = m;
        best_k = k;
        best_lo = lo;
        best_hi = std::max(hi, lo + 1);
      }
    }
  }
  best.step = best_m * power_of_ten(best_k);
  for (long i = best_lo; i <= best_hi; ++i) {
    double v = tick_value(i, best_m, best_k);
    if (std::abs(v) < best.step * 1e-9) v = 0.0;
    best.values.push_back(v);
  }
  best.lo = best.values.front();
  best.hi = best.values.back();
  return best;
}

LogTicks log_ticks(double min_positive, double max_positive, int target_count) {
  const int target = std::max(target_count, 2);
  const bool min_ok = std::isfinite(min_positive) && min_positive > 0.0;
  const bool max_ok = std::isfinite(max_positive) && max_positive > 0.0;
  if (!min_ok && !max_ok) {
    min_positive = 1.0;
    max_positive = 10.0;
  } else if (!min_ok) {
    min_positive = max_positive;
  } else if (!max_ok) {
    max_positive = min_positive;
  }
  if (min_positive > max_positive) std::swap(min_positive, max_positive);
  LogTicks t;
  t.lo_exp = static_cast<int>(std::floor(std::log10(min_positive) + 1e-9));
  t.hi_exp = static_cast<int>(std::ceil(std::log10(max_positive) - 1e-9));
  if (t.hi_exp <= t.lo_exp) t.hi_exp = t.lo_exp + 1;
  const int decades = t.hi_exp - t.lo_exp;
  t.decade_step = std::max(1, (decades + target - 2) / (target - 1));
  const int steps = (decades + t.decade_step - 1) / t.decade_step;
  t.hi_exp = t.lo_exp + steps * t.decade_step;
  for (int e = t.lo_exp; e <= t.hi_exp; e += t.decade_step) t.major_exponents.push_back(e);
  if (t.decade_step == 1 && decades <= 6) {
    for (int e = t.lo_exp; e < t.hi_exp; ++e) {
      for (int m = 2; m <= 9; ++m) t.minor_values.push_back(m * std::pow(10.0, e));
    }
  }
  return t;
}

std::string format_fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", std::clamp(decimals, 0, 20), value);
  std::string s(buffer);
  if (!s.empty() && s[0] == '-') {
    const bool zero = s.find_first_not_of("0.", 1) == std::string::npos;
    s = zero ? s.substr(1) : "\u2212" + s.substr(1);
  }
  return s;
}

TickLabels format_ticks(const Ticks& ticks) {
  TickLabels out;
  const int k = static_cast<int>(std::floor(std::log10(ticks.step) + 1e-9));
  const double magnitude = std::max(std::abs(ticks.lo), std::abs(ticks.hi));
  int decimals = std::max(0, -k);
  double divisor = 1.0;
  if (magnitude > 0.0 && (magnitude >= 1e5 || magnitude < 1e-3)) {
    out.exponent = static_cast<int>(std::floor(std::log10(magnitude) + 1e-9));
    divisor = std::pow(10.0, out.exponent);
    decimals = std::max(0, out.exponent - k);
  }
  for (double v : ticks.values) out.labels.push_back(format_fixed(v / divisor, decimals));
  return out;
}

}  // namespace stiction::plot
