// Reading scene tables with exact error positions. A TableReader remembers every key it
// was asked for; finish() then reports the first key nobody read as "unknown key", so a typo
// in a scene file is an error, not a silently ignored value. Every error is an InputError
// whose message is "FILE:LINE:COL: error: ..." naming the key (DESIGN section 3).
#pragma once

#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "core/types.hpp"

namespace stiction::scene {

// Bad input: a scene file, an override or a command-line value. Exit code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // "FILE:LINE:COL: error: MESSAGE" from a toml++ source region (file "-" if unknown).
  static InputError at(const toml::source_region& where, const std::string& message);
};

// The value of a number node as a double: floats as they are, integers only up to 2^53 in
// magnitude (beyond that a double no longer holds every integer, and toml++ refuses the
// conversion). `what` names the key in the message. InputError at the node otherwise, also
// for NaN and infinities.
double finite_number(const toml::node& node, const std::string& what);
// The same, but infinities (TOML `inf`, `-inf`) are allowed: NaN is not.
double number_or_infinity(const toml::node& node, const std::string& what);

class TableReader {
 public:
  // `path` is the dotted path of the table ("bodies.sphere"), used in messages.
  TableReader(const toml::table& table, std::string path);

  const std::string& path() const { return path_; }
  const toml::table& table() const { return table_; }
  bool has(std::string_view key) const;

  // Typed reads. A missing key gives the default; a value of the wrong type is an error.
  double number(std::string_view key, double fallback);
  double required_number(std::string_view key);
  // Numbers with a range check (error names the key and the allowed range).
  double positive(std::string_view key, double fallback);         // > 0
  double non_negative(std::string_view key, double fallback);     // >= 0
  long integer(std::string_view key, long fallback);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, const std::string& fallback);
  std::string required_string(std::string_view key);
  core::Vec3 vec3(std::string_view key, const core::Vec3& fallback);
  std::vector<double> numbers(std::string_view key);               // array of numbers, may be empty
  std::vector<std::string> strings(std::string_view key);          // array of strings, may be empty
  std::optional<TableReader> subtable(std::string_view key);
  std::vector<TableReader> array_of_tables(std::string_view key);
  // Marks a key as read and returns its node (nullptr if absent), for custom parsing.
  const toml::node* node(std::string_view key);

  // Error at the key's value (or at the table if the key is absent).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  // Error at the first key of this table that no read asked for.
  void finish() const;

 private:
  const toml::table& table_;
  std::string path_;
  std::set<std::string, std::less<>> read_;
};

}  // namespace stiction::scene
