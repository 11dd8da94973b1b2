// Numbers as text, by one rule everywhere the program prints a number for a reader (console
// lines, tables, figure labels; summary.json is written by its JSON library, which already
// writes the shortest round-trip form):
//   - a value the reader may copy back (a parameter, a sweep value, a step) is printed
//     shortest round-trip: 0.15, not 0.15000000000000002; 1e-05, not 1.0000000000000001e-05;
//   - a measured value (an event time, an error, a wall time) is printed with a stated number
//     of significant digits, trailing zeros dropped, the same count for every value of a kind:
//     every event time, stick or slip, with kEventTimeDigits.
#pragma once

#include <string>

namespace stiction::text {

// Significant digits of an event time on the console and in labels (1 us at 1..10 s).
inline constexpr int kEventTimeDigits = 7;
// Significant digits of a time in a figure's event label (1 ms at 0.1..1 s).
inline constexpr int kLabelTimeDigits = 4;

// The shortest text that reads back as exactly `value` ("0.15", "-2", "1e-05", "inf", "nan").
std::string shortest(double value);

// `value` with `digits` significant digits (1..17), trailing zeros and a trailing point
// dropped, scientific notation outside 1e-4..1e+digits as printf's %g does ("0.5843614",
// "1.3999", "2e-07").
std::string significant(double value, int digits);

}  // namespace stiction::text
