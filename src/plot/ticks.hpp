// Axis ranges and tick values: "nice" 1-2-5 steps for linear axes, decades for log axes,
// and the labels printed beside them. Pure functions, no drawing.
#pragma once

#include <string>
#include <vector>

namespace stiction::plot {

// A linear axis: the range [lo, hi] is the data range widened to whole steps, so the axis
// starts and ends on a labelled tick. values are lo, lo + step, ..., hi (at least two).
struct Ticks {
  double lo = 0.0;
  double hi = 1.0;
  double step = 0.5;
  std::vector<double> values;
};

// Ticks for data in [min, max] with a step of 1, 2 or 5 times a power of ten, chosen so the
// number of ticks inside [min, max] is as close as possible to target_count (>= 2), with at
// least two inside whenever a candidate step allows it; ties go to the larger step.
// Handles min > max (swapped), a flat range (min == max: a small range around the value,
// [-1, 1] around 0) and non-finite input (ignored: both non-finite gives [0, 1]). A range
// narrower than 1e-12 of its magnitude is treated as flat. Values within step*1e-9 of zero
// are exactly 0. Never returns NaN.
Ticks nice_ticks(double min, double max, int target_count = 6);

// Range of the finite values in data; {NaN, NaN} when there are none (nice_ticks accepts
// that and gives [0, 1]).
struct Range {
  double min;
  double max;
};
Range finite_range(const std::vector<double>& data);
// Like finite_range but only positive values (for log axes).
Range positive_range(const std::vector<double>& data);

// A log axis: decades lo_exp..hi_exp (the axis runs 10^lo_exp .. 10^hi_exp); major ticks
// every `decade_step` decades (labelled), minor ticks at 2..9 times each decade when the
// axis spans at most 6 decades. Non-positive or non-finite input is ignored; no positive
// data gives 10^0 .. 10^1. A range within one decade still spans a whole decade.
struct LogTicks {
  int lo_exp = 0;
  int hi_exp = 1;
  int decade_step = 1;
  std::vector<int> major_exponents;
  std::vector<double> minor_values;
};
LogTicks log_ticks(double min_positive, double max_positive, int target_count = 6);

// Labels for linear ticks. Plain decimals when the ticks are between 1e-3 and 1e5 in size;
// otherwise the labels are mantissas and `exponent` is the power of ten to print once at the
// axis ("×10^exponent"). Negative numbers use the Unicode minus sign (U+2212).
struct TickLabels {
  std::vector<std::string> labels;
  int exponent = 0;  // 0: no common factor
};
TickLabels format_ticks(const Ticks& ticks);

// A number with `decimals` digits after the point and a Unicode minus; "-0" prints as "0".
std::string format_fixed(double value, int decimals);

}  // namespace stiction::plot
