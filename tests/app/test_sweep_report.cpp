// What a sweep prints for a reader (issue 21): range values as the decimals they stand for
// (0.15, not 0.15000000000000002), sweep.md's measured records by the number rule, and the
// figure's lines in numeric order of the other keys' values (-40, -20, 0, 5).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "services/sweep.hpp"

using namespace stiction;
using services::SweepPlan;
using services::SweepTable;

namespace {

// The decimal text of n / 10^decimals ("-0.15" for -15, 2).
std::string decimal(long n, int decimals) {
  const std::string digits = std::to_string(std::labs(n));
  const std::size_t places = static_cast<std::size_t>(decimals);
  const std::string padded =
      std::string(digits.size() <= places ? places + 1 - digits.size() : 0, '0') + digits;
  const std::size_t point = padded.size() - places;
  const std::string text =
      places == 0 ? padded : padded.substr(0, point) + "." + padded.substr(point);
  return n < 0 ? "-" + text : text;
}

// A table of two keys: `mu` along x, `v0` telling the lines apart, one record.
SweepTable table_of(const std::vector<std::string>& mus, const std::vector<std::string>& v0s,
                    const std::string& record) {
  SweepTable table;
  table.header = {"point",  "mu",           "v0",   "status",           "steps",
                  "wall_s", "suggested_dt", "note", "ground.stick_time"};
  std::size_t index = 0;
  for (const std::string& mu : mus) {
    for (const std::string& v0 : v0s) {
      table.rows[index] = {std::to_string(index), mu, v0, "ok", "10", "0.001", "", "", record};
      ++index;
    }
  }
  return table;
}

SweepPlan plan_of(const std::vector<std::string>& mus, const std::vector<std::string>& v0s) {
  SweepPlan plan;
  plan.scene = "s";
  plan.keys = {{"mu", mus}, {"v0", v0s}};
  plan.points = services::make_points(plan.keys, false);
  plan.columns = table_of(mus, v0s, "").header;
  plan.plot = {"ground.stick_time"};
  return plan;
}

}  // namespace

TEST_CASE("sweep ranges are the decimals they stand for", "[sweep]") {
  // The cases of the issue and the docs, then generated ranges of decimals.
  CHECK(services::parse_vary("k=0.05:0.25:5").values ==
        std::vector<std::string>{"0.05", "0.1", "0.15", "0.2", "0.25"});
  CHECK(services::parse_vary("k=0.05:0.5:10").values[8] == "0.45");
  CHECK(services::parse_vary("k=1e-5:1e-3:3:log").values ==
        std::vector<std::string>{"1e-05", "1e-04", "0.001"});
  std::mt19937 rng(21);
  for (int trial = 0; trial < 300; ++trial) {
    const int decimals = std::uniform_int_distribution<int>(0, 4)(rng);
    const long start = std::uniform_int_distribution<long>(-5000, 5000)(rng);
    const long step = std::uniform_int_distribution<long>(1, 3000)(rng);
    const long count = std::uniform_int_distribution<long>(2, 40)(rng);
    const std::string range = decimal(start, decimals) + ":" +
                              decimal(start + step * (count - 1), decimals) + ":" +
                              std::to_string(count);
    INFO(range);
    const std::vector<std::string> values = services::parse_vary("k=" + range).values;
    REQUIRE(values.size() == static_cast<std::size_t>(count));
    for (long i = 0; i < count; ++i) {
      // The value read back is the double nearest the decimal: its shortest text is short.
      CHECK(std::stod(values[static_cast<std::size_t>(i)]) ==
            std::stod(decimal(start + step * i, decimals)));
    }
  }
}

TEST_CASE("sweep.md prints parameters as given and measured records by the number rule",
          "[sweep]") {
  const std::vector<std::string> mus{"0.15", "0.3"}, v0s{"1"};
  const std::string md =
      services::sweep_markdown(plan_of(mus, v0s), table_of(mus, v0s, "0.020300000000000002"));
  INFO(md);
  CHECK(md.find("| 0 | 0.15 | 1 | ok | 10 | 0.001 | 0.0203 |") != std::string::npos);
  CHECK(md.find("0.020300000000000002") == std::string::npos);
}

TEST_CASE("sweep figure lines follow the numeric order of the other keys' values", "[sweep]") {
  // Values given in any order, negative and positive: the lines (and legend) sorted as numbers.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> numbers;
    for (int i = 0; i < std::uniform_int_distribution<int>(2, 8)(rng); ++i) {
      const double v = std::uniform_int_distribution<int>(-500, 500)(rng) * 0.25;
      if (std::find(numbers.begin(), numbers.end(), v) == numbers.end()) numbers.push_back(v);
    }
    std::vector<std::string> v0s;
    for (double v : numbers) {
      std::ostringstream text;
      text << v;
      v0s.push_back(text.str());
    }
    const std::vector<std::string> mus{"0.1", "0.2"};
    const plot::Figure figure =
        services::sweep_figure(plan_of(mus, v0s), table_of(mus, v0s, "0.5"));
    REQUIRE(figure.panels.size() == 1);
    std::vector<double> order;
    for (const plot::Series& s : figure.panels[0].series) {
      REQUIRE(s.label.rfind("v0 = ", 0) == 0);
      order.push_back(std::stod(s.label.substr(5)));
    }
    INFO("values " << ::Catch::Detail::stringify(v0s));
    CHECK(order.size() == numbers.size());
    CHECK(std::is_sorted(order.begin(), order.end()));
    REQUIRE(figure.print);
    CHECK(figure.print->width_mm == 88.0);
  }
  // Text values sort as text, after nothing in particular but stably.
  const std::vector<std::string> words{"\"b\"", "\"a\""};
  const plot::Figure figure =
      services::sweep_figure(plan_of({"0.1"}, words), table_of({"0.1"}, words, "0.5"));
  REQUIRE(figure.panels[0].series.size() == 2);
  CHECK(figure.panels[0].series[0].label == "v0 = \"a\"");
  // A line without any value of the record is left out (no empty legend entry).
  const plot::Figure empty = services::sweep_figure(plan_of({"0.1"}, {"1", "2"}), [] {
    SweepTable t = table_of({"0.1"}, {"1", "2"}, "0.5");
    t.rows[1][8] = "";
    return t;
  }());
  REQUIRE(empty.panels[0].series.size() == 1);
  CHECK(empty.panels[0].series[0].label == "v0 = 1");
}
