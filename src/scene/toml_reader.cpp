#include "scene/toml_reader.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

namespace stiction::scene {
namespace {

std::string describe(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

std::string format_number(double v) {
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

}  // namespace

namespace {

// The number as it is (integers only up to 2^53), NaN and infinities included.
double any_number(const toml::node& node, const std::string& what) {
  constexpr std::int64_t kExact = std::int64_t{1} << 53;
  if (const auto* i = node.as_integer()) {
    const std::int64_t v = i->get();
    if (v > kExact || v < -kExact) {
      throw InputError::at(node.source(), what + ": the integer " + std::to_string(v) +
                                              " is beyond 2^53 = 9007199254740992, the largest "
                                              "a number holds exactly (write it as a float, e.g. 1e16)");
    }
    return static_cast<double>(v);
  }
  const auto* f = node.as_floating_point();
  if (f == nullptr) throw InputError::at(node.source(), what + ": expected a number, got " + describe(node));
  return f->get();
}

}  // namespace

double number_or_infinity(const toml::node& node, const std::string& what) {
  const double v = any_number(node, what);
  if (std::isnan(v)) throw InputError::at(node.source(), what + ": expected a number (inf allowed), got nan");
  return v;
}

double finite_number(const toml::node& node, const std::string& what) {
  const double v = any_number(node, what);
  if (!std::isfinite(v)) throw InputError::at(node.source(), what + ": expected a finite number");
  return v;
}

InputError InputError::at(const toml::source_region& where, const std::string& message) {
  std::ostringstream out;
  out << (where.path ? *where.path : std::string("-")) << ':' << where.begin.line << ':'
      << where.begin.column << ": error: " << message;
  return InputError(out.str());
}

TableReader::TableReader(const toml::table& table, std::string path)
    : table_(table), path_(std::move(path)) {}

bool TableReader::has(std::string_view key) const { return table_.contains(key); }

const toml::node* TableReader::node(std::string_view key) {
  read_.emplace(key);
  return table_.get(key);
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  const std::string full = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  if (const toml::node* n = table_.get(key)) throw InputError::at(n->source(), full + ": " + message);
  throw InputError::at(table_.source(), full + ": " + message);
}

void TableReader::finish() const {
  // The first unread key in file order, so the report matches what a reader sees first.
  const toml::key* first = nullptr;
  for (const auto& [key, value] : table_) {
    if (read_.contains(key.str())) continue;
    const auto& a = key.source().begin;
    if (!first || a.line < first->source().begin.line ||
        (a.line == first->source().begin.line && a.column < first->source().begin.column)) {
      first = &key;
    }
  }
  if (!first) return;
  const std::string name(first->str());
  const std::string full = path_.empty() ? name : path_ + "." + name;
  // A key inserted by an override has no position of its own; its value has.
  const toml::source_region& where =
      first->source().path ? first->source() : table_.get(first->str())->source();
  throw InputError::at(where, "unknown key '" + full + "'");
}

double TableReader::number(std::string_view key, double fallback) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_number()) fail(key, "expected a number, got " + describe(*n));
  return finite_number(*n, path_.empty() ? std::string(key) : path_ + "." + std::string(key));
}

double TableReader::required_number(std::string_view key) {
  if (!has(key)) fail(key, "missing (a number is required)");
  return number(key, 0.0);
}

double TableReader::positive(std::string_view key, double fallback) {
  const double v = number(key, fallback);
  if (!(v > 0.0)) fail(key, "must be > 0 (got " + format_number(v) + ")");
  return v;
}

double TableReader::non_negative(std::string_view key, double fallback) {
  const double v = number(key, fallback);
  if (!(v >= 0.0)) fail(key, "must be >= 0 (got " + format_number(v) + ")");
  return v;
}

long TableReader::integer(std::string_view key, long fallback) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_integer()) fail(key, "expected an integer, got " + describe(*n));
  return static_cast<long>(n->as_integer()->get());
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_boolean()) fail(key, "expected true or false, got " + describe(*n));
  return n->as_boolean()->get();
}

std::string TableReader::string(std::string_view key, const std::string& fallback) {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_string()) fail(key, "expected a string, got " + describe(*n));
  return n->as_string()->get();
}

std::string TableReader::required_string(std::string_view key) {
  if (!has(key)) fail(key, "missing (a string is required)");
  return string(key, {});
}

core::Vec3 TableReader::vec3(std::string_view key, const core::Vec3& fallback) {
  if (!has(key)) {
    read_.emplace(key);
    return fallback;
  }
  const std::vector<double> v = numbers(key);
  if (v.size() != 3) fail(key, "expected 3 numbers, got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

std::vector<double> TableReader::numbers(std::string_view key) {
  const toml::node* n = node(key);
  std::vector<double> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) fail(key, "expected an array of numbers, got " + describe(*n));
  for (const toml::node& e : *a) {
    if (!e.is_number()) {
      throw InputError::at(e.source(), (path_.empty() ? "" : path_ + ".") + std::string(key) +
                                           ": expected a number, got " + describe(e));
    }
    out.push_back(finite_number(e, (path_.empty() ? "" : path_ + ".") + std::string(key)));
  }
  return out;
}

std::vector<std::string> TableReader::strings(std::string_view key) {
  const toml::node* n = node(key);
  std::vector<std::string> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) fail(key, "expected an array of strings, got " + describe(*n));
  for (const toml::node& e : *a) {
    if (!e.is_string()) {
      throw InputError::at(e.source(), (path_.empty() ? "" : path_ + ".") + std::string(key) +
                                           ": expected a string, got " + describe(e));
    }
    out.push_back(e.as_string()->get());
  }
  return out;
}

std::optional<TableReader> TableReader::subtable(std::string_view key) {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_table()) fail(key, "expected a table, got " + describe(*n));
  return TableReader(*n->as_table(), path_.empty() ? std::string(key) : path_ + "." + std::string(key));
}

std::vector<TableReader> TableReader::array_of_tables(std::string_view key) {
  const toml::node* n = node(key);
  std::vector<TableReader> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) fail(key, "expected an array of tables, got " + describe(*n));
  const std::string base = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = (*a)[i];
    if (!e.is_table()) {
      throw InputError::at(e.source(), base + "[" + std::to_string(i) + "]: expected a table, got " +
                                           describe(e));
    }
    out.emplace_back(*e.as_table(), base + "[" + std::to_string(i) + "]");
  }
  return out;
}

}  // namespace stiction::scene
