#include <catch2/catch.hpp>
#include <cmath>

#include "plot/ticks.hpp"

using namespace stiction::plot;

namespace {

// The step is 1, 2 or 5 times a power of ten.
bool is_nice_step(double step) {
  const double k = std::floor(std::log10(step) + 1e-9);
  const double m = step / std::pow(10.0, k);
  return std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9;
}

void check_ticks(const Ticks& t, double min, double max, int target) {
  INFO("range [" << min << ", " << max << "], step " << t.step << ", " << t.values.size()
                 << " ticks");
  REQUIRE(t.values.size() >= 2);
  CHECK(is_nice_step(t.step));
  // The ticks enclose the data (up to the rounding of the tick values).
  CHECK(t.lo <= min + 1e-9 * t.step);
  CHECK(t.hi >= max - 1e-9 * t.step);
  CHECK(t.lo == t.values.front());
  CHECK(t.hi == t.values.back());
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    CHECK(std::isfinite(t.values[i]));
    // Multiples of the step, evenly spaced.
    const double q = t.values[i] / t.step;
    CHECK(std::abs(q - std::round(q)) < 1e-6);
    if (i > 0) CHECK(t.values[i] - t.values[i - 1] == Approx(t.step).epsilon(1e-9));
  }
  // Close to the requested count: a 1-2-5 sequence always has a step within a factor 2.5.
  CHECK(static_cast<int>(t.values.size()) <= 2 * target + 1);
  CHECK(static_cast<int>(t.values.size()) >= std::max(2, target / 2));
}

}  // namespace

TEST_CASE("nice ticks use 1-2-5 steps over ranges from 1e-12 to 1e6", "[plot][ticks]") {
  for (int e = -12; e <= 6; ++e) {
    const double span = std::pow(10.0, e);
    for (double factor : {1.0, 1.7, 3.3, 7.1}) {
      for (double offset : {0.0, 0.31, -2.5}) {
        const double min = offset * span, max = min + factor * span;
        for (int target : {4, 6, 10}) check_ticks(nice_ticks(min, max, target), min, max, target);
      }
    }
  }
}

TEST_CASE("nice ticks of known ranges", "[plot][ticks]") {
  const Ticks a = nice_ticks(0.0, 1.0, 6);
  CHECK(a.step == 0.2);
  CHECK(a.values == std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0});
  const Ticks b = nice_ticks(0.0, 15.0, 6);
  CHECK(b.step == 5.0);
  CHECK(b.values == std::vector<double>{0, 5, 10, 15});
  const Ticks c = nice_ticks(0.0, 1e-12, 6);
  CHECK(c.step == Approx(2e-13));
  CHECK(c.values.back() == Approx(1e-12));
  const Ticks d = nice_ticks(0.0, 1e6, 6);
  CHECK(d.step == 2e5);
}

TEST_CASE("nice ticks of negative ranges", "[plot][ticks]") {
  const Ticks t = nice_ticks(-7.3, -0.2, 6);
  check_ticks(t, -7.3, -0.2, 6);
  CHECK(t.hi <= 0.0);
  CHECK(t.lo >= -10.0);
  const Ticks u = nice_ticks(-0.52, 0.52, 5);
  check_ticks(u, -0.52, 0.52, 5);
  // Zero is a tick, exactly.
  CHECK(std::find(u.values.begin(), u.values.end(), 0.0) != u.values.end());
  // Swapped bounds give the same ticks.
  CHECK(nice_ticks(-0.2, -7.3, 6).values == t.values);
}

TEST_CASE("a flat series gets a small range around its value", "[plot][ticks]") {
  const Ticks t = nice_ticks(0.336, 0.336, 5);
  check_ticks(t, 0.336, 0.336, 5);
  CHECK(t.lo < 0.336);
  CHECK(t.hi > 0.336);
  CHECK(t.hi - t.lo < 0.2);
  const Ticks z = nice_ticks(0.0, 0.0, 5);
  CHECK(z.lo == -1.0);
  CHECK(z.hi == 1.0);
  const Ticks big = nice_ticks(-4.2e6, -4.2e6, 5);
  check_ticks(big, -4.2e6, -4.2e6, 5);
  // A range below double resolution of its magnitude is flat too, never a zero step.
  const Ticks tiny = nice_ticks(1.0, 1.0 + 1e-15, 5);
  CHECK(tiny.step > 0.0);
  CHECK(tiny.values.size() < 20);
}

TEST_CASE("an empty series gives a finite default range", "[plot][ticks]") {
  const Range r = finite_range({});
  CHECK(std::isnan(r.min));
  const Ticks t = nice_ticks(r.min, r.max, 6);
  CHECK(t.lo == 0.0);
  CHECK(t.hi == 1.0);
  for (double v : t.values) CHECK(std::isfinite(v));
  const Range nans = finite_range({NAN, INFINITY, -INFINITY});
  CHECK(nice_ticks(nans.min, nans.max, 6).values == t.values);
  const Range mixed = finite_range({NAN, 2.0, -1.0, INFINITY});
  CHECK(mixed.min == -1.0);
  CHECK(mixed.max == 2.0);
  const LogTicks l = log_ticks(NAN, NAN, 6);
  CHECK(l.lo_exp == 0);
  CHECK(l.hi_exp == 1);
}

TEST_CASE("log ticks cover whole decades", "[plot][ticks]") {
  const LogTicks a = log_ticks(3e-13, 2e-1, 6);
  CHECK(a.lo_exp == -13);
  CHECK(a.hi_exp >= 0);
  CHECK(a.decade_step == 3);
  CHECK(a.major_exponents.front() == -13);
  CHECK(a.minor_values.empty());
  const LogTicks b = log_ticks(0.02, 30.0, 6);
  CHECK(b.lo_exp == -2);
  CHECK(b.hi_exp == 2);
  CHECK(b.decade_step == 1);
  CHECK(b.minor_values.size() == 4 * 8);
  const LogTicks c = log_ticks(1e-3, 1e-3, 6);  // flat: one decade
  CHECK(c.lo_exp == -3);
  CHECK(c.hi_exp == -2);
  const Range p = positive_range({-1.0, 0.0, 5.0, 0.5});
  CHECK(p.min == 0.5);
  CHECK(p.max == 5.0);
}

TEST_CASE("tick labels", "[plot][ticks]") {
  CHECK(format_fixed(-0.0001, 2) == "0.00");
  CHECK(format_fixed(-1.5, 1) == "\u22121.5");
  CHECK(format_fixed(2.0, 0) == "2");
  const TickLabels a = format_ticks(nice_ticks(0.0, 1.0, 6));
  CHECK(a.exponent == 0);
  CHECK(a.labels == std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"});
  const TickLabels b = format_ticks(nice_ticks(0.0, 1e-12, 6));
  CHECK(b.exponent == -12);
  CHECK(b.labels.back() == "1.0");
  const TickLabels c = format_ticks(nice_ticks(0.0, 1e6, 6));
  CHECK(c.exponent == 6);
  CHECK(c.labels[1] == "0.2");
  const TickLabels d = format_ticks(nice_ticks(-10.0, 10.0, 5));
  CHECK(d.labels.front() == "\u221210");
  // Labels of distinct ticks are distinct.
  for (int e = -12; e <= 6; ++e) {
    const TickLabels l = format_ticks(nice_ticks(0.3 * std::pow(10.0, e), std::pow(10.0, e), 6));
    for (std::size_t i = 1; i < l.labels.size(); ++i) CHECK(l.labels[i] != l.labels[i - 1]);
  }
}
