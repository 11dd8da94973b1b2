#include "services/sweep_plan.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "io/csv_writer.hpp"
#include "scene/toml_reader.hpp"
#include "text/number_text.hpp"

namespace stiction::services {
namespace {

scene::InputError bad_vary(const std::string& argument, std::size_t column,
                           const std::string& why) {
  return scene::InputError("--vary " + argument + ":1:" + std::to_string(column + 1) +
                           ": error: " + why);
}

std::optional<double> parse_double(const std::string& text) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::size_t> parse_count(const std::string& text) {
  std::size_t v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return v;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(separator, start);
    parts.push_back(text.substr(start, at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

std::string number_text(double v) {
  std::string s;
  io::append_number(s, v);
  return s;
}

// A point of a range as the decimal it stands for: start + f (stop - start) picks up the
// rounding of binary fractions (0.05:0.25:5 gave 0.15000000000000002, 0.05:0.5:10 gave
// 0.44999999999999996), a few units in the last place of `scale`, the larger end. Rounded
// to 14 significant digits of `scale` (a point of -4.716:9.629 near 0.569 keeps 13 of its
// own), the error goes; a point within that rounding of zero is zero.
double range_value(double v, double scale) {
  if (v == 0.0 || !(scale > 0.0)) return v;
  const int digits = 14 + static_cast<int>(std::floor(std::log10(std::abs(v)))) -
                     static_cast<int>(std::floor(std::log10(scale)));
  if (digits < 1) return 0.0;
  return std::stod(text::significant(v, std::min(digits, 17)));
}

// start:stop:count[:log]
std::vector<std::string> range_values(const std::string& argument, std::size_t column,
                                      const std::string& list) {
  const std::vector<std::string> parts = split(list, ':');
  if (parts.size() != 3 && !(parts.size() == 4 && parts[3] == "log")) {
    throw bad_vary(argument, column, "a range is start:stop:count or start:stop:count:log");
  }
  const auto start = parse_double(parts[0]);
  const auto stop = parse_double(parts[1]);
  const auto count = parse_count(parts[2]);
  if (!start || !stop) throw bad_vary(argument, column, "range ends must be finite numbers");
  if (!count || *count < 1 || *count > kMaxSweepPoints) {
    throw bad_vary(argument, column,
                   "range count must be an integer in 1.." + std::to_string(kMaxSweepPoints));
  }
  const bool log = parts.size() == 4;
  if (log && !(*start > 0.0 && *stop > 0.0)) {
    throw bad_vary(argument, column, "a :log range needs start > 0 and stop > 0");
  }
  std::vector<std::string> values;
  for (std::size_t i = 0; i < *count; ++i) {
    double v = *start;
    if (*count > 1) {
      const double f = static_cast<double>(i) / static_cast<double>(*count - 1);
      v = log ? *start * std::pow(*stop / *start, f) : *start + f * (*stop - *start);
    }
    if (i + 1 == *count) v = *stop;  // the end exactly, whatever the rounding
    // A geometric point's error is relative to itself, an arithmetic one's to the ends.
    values.push_back(number_text(
        range_value(v, log ? std::abs(v) : std::max(std::abs(*start), std::abs(*stop)))));
  }
  return values;
}

}  // namespace

VaryKey parse_vary(const std::string& argument) {
  const std::size_t eq = argument.find('=');
  if (eq == std::string::npos || eq == 0) throw bad_vary(argument, 0, "expected KEY=LIST");
  VaryKey vary;
  vary.key = argument.substr(0, eq);
  const std::string list = argument.substr(eq + 1);
  if (list.empty()) throw bad_vary(argument, eq + 1, "empty list of values");
  // A TOML string or array may itself contain ':' or ','; ranges are plain numbers.
  const bool quoted = list.find_first_of("\"'[{") != std::string::npos;
  if (!quoted && list.find(':') != std::string::npos) {
    vary.values = range_values(argument, eq + 1, list);
  } else if (!quoted) {
    std::size_t column = eq + 1;
    for (const std::string& v : split(list, ',')) {
      if (v.empty()) throw bad_vary(argument, column, "empty value in the list");
      vary.values.push_back(v);
      column += v.size() + 1;
    }
  } else {
    vary.values.push_back(list);  // one TOML value (a string, an array): no splitting
  }
  return vary;
}

std::vector<SweepPoint> make_points(const std::vector<VaryKey>& keys, bool zip, std::size_t limit) {
  std::vector<SweepPoint> points;
  if (keys.empty()) return points;
  if (zip) {
    const std::size_t n = keys.front().values.size();
    for (const VaryKey& k : keys) {
      if (k.values.size() != n) {
        throw scene::InputError("error: --zip: --vary " + keys.front().key + " has " +
                                std::to_string(n) + " values but --vary " + k.key + " has " +
                                std::to_string(k.values.size()));
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      SweepPoint p{i, {}};
      for (const VaryKey& k : keys) p.values.push_back(k.values[i]);
      points.push_back(std::move(p));
    }
    return points;
  }
  double total = 1.0;
  for (const VaryKey& k : keys) total *= static_cast<double>(k.values.size());
  if (total > static_cast<double>(limit)) {
    throw scene::InputError("error: --vary: the grid has " + number_text(total) +
                            " points, more than " + std::to_string(limit) +
                            " (a plan holds about 370 bytes a point before the first runs); "
                            "split it over several sweeps");
  }
  const std::size_t count = static_cast<std::size_t>(total);
  for (std::size_t i = 0; i < count; ++i) {
    SweepPoint p{i, std::vector<std::string>(keys.size())};
    std::size_t rest = i;
    for (std::size_t k = keys.size(); k-- > 0;) {  // last key fastest
      p.values[k] = keys[k].values[rest % keys[k].values.size()];
      rest /= keys[k].values.size();
    }
    points.push_back(std::move(p));
  }
  return points;
}

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  const auto k = slash == std::string::npos ? std::nullopt : parse_count(text.substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : parse_count(text.substr(slash + 1));
  if (!k || !n || *n < 1 || *k >= *n) {
    throw scene::InputError("--shard " + text + ":1:1: error: expected K/N with 0 <= K < N");
  }
  return Shard{*k, *n};
}

std::optional<Shard> shard_from_environment() {
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (id == nullptr || count == nullptr) return std::nullopt;
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  const auto i = parse_count(id);
  const auto n = parse_count(count);
  const auto m = min != nullptr ? parse_count(min) : std::optional<std::size_t>(0);
  if (!i || !n || !m || *i < *m || *n < 1 || *i - *m >= *n) {
    throw scene::InputError(std::string("error: SLURM_ARRAY_TASK_ID=") + id +
                            ", SLURM_ARRAY_TASK_COUNT=" + count +
                            " make no shard (a contiguous array MIN..MIN+COUNT-1 is expected)");
  }
  return Shard{*i - *m, *n};
}

}  // namespace stiction::services
