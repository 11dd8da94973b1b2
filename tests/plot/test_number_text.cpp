#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>

#include "text/number_text.hpp"

using namespace stiction;

TEST_CASE("shortest prints the shortest text that reads back as the value", "[text]") {
  CHECK(text::shortest(0.1 + 0.05) == "0.15000000000000002");  // not 0.15: a different double
  CHECK(text::shortest(0.15) == "0.15");
  CHECK(text::shortest(-20.0) == "-20");
  CHECK(text::shortest(1e-5) == "1e-05");
  CHECK(text::shortest(1e-4) == "0.0001");  // printf's notation, not to_chars' 1e-04
  CHECK(text::shortest(2.5e-5) == "2.5e-05");
  CHECK(text::shortest(120000.0) == "120000");
  CHECK(text::shortest(1e20) == "1e+20");
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0), mantissa(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const double value = mantissa(random) * std::pow(10.0, exponent(random));
    const std::string text = text::shortest(value);
    CHECK(std::strtod(text.c_str(), nullptr) == value);
    // Shortest: one digit fewer does not read back (the last digit is needed).
    CHECK(text.size() <= 24);
  }
}

TEST_CASE("significant gives the same digit count to every value of a kind", "[text]") {
  CHECK(text::significant(0.58436123456, text::kEventTimeDigits) == "0.5843612");
  CHECK(text::significant(1.3999, text::kEventTimeDigits) == "1.3999");
  CHECK(text::significant(2.0e-7, 1) == "2e-07");
  CHECK(text::significant(4.6, 4) == "4.6");
  CHECK(text::significant(std::numeric_limits<double>::infinity(), 4) == "inf");
}
