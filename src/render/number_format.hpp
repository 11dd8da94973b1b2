// Numbers for the video overlay: four significant digits, scaled with an SI prefix when the
// unit takes one ("0.0044 m/s" reads "4.400 mm/s", "4.71e-06 m/s" reads "4.710 um/s"), so
// the reader sees the magnitude at every scale and the digits never switch between fixed
// and scientific notation. Units that take no prefix (or none given) fall back to
// "1.234e-05" outside 0.01..9999.
#pragma once

#include <string>
#include <vector>

namespace stiction::render {

struct Quantity {
  std::string number;  // "-12.34"
  std::string unit;    // "mm/s", possibly empty
};

// `zero_below`: magnitudes under it print as zero (rounding noise of a stuck contact would
// otherwise read "1.776 fm/s"); the overlay uses 1e-9 times the signal's largest magnitude.
Quantity format_quantity(double value, const std::string& unit, double zero_below = 0.0);

// True if `unit` starts with a symbol that takes an SI prefix (m, s, N, rad, J, W, Pa, Hz,
// A, V): "m/s", "N m", "rad/s2"; not "kg", "deg" or "".
bool takes_si_prefix(const std::string& unit);

// Every unit string format_quantity may produce for `unit` (for sizing a fixed-width box).
std::vector<std::string> possible_units(const std::string& unit);

// Strings as wide as the widest number format_quantity can produce for `unit` (with every
// digit 0..9 in each place): measure them all and keep the widest.
std::vector<std::string> widest_number_candidates(const std::string& unit);

}  // namespace stiction::render
