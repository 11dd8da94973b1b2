#include "scene/toml_parse_error.hpp"

namespace stiction::scene {
namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// Line `line` (1-based) of `text`, without its newline.
std::string_view line_of(std::string_view text, std::size_t line) {
  std::size_t start = 0;
  for (std::size_t l = 1; l < line; ++l) {
    const std::size_t next = text.find('\n', start);
    if (next == std::string_view::npos) return {};
    start = next + 1;
  }
  const std::size_t end = text.find('\n', start);
  return text.substr(start, end == std::string_view::npos ? text.size() - start : end - start);
}

// The name a line defines: a table header's inside ([a.b], [[a.b]]), or a key before '='
// (quotes respected: an '=' inside a quoted key is part of it).
std::string defined_name(std::string_view line) {
  line = trimmed(line);
  if (line.starts_with('[')) {
    const bool array = line.starts_with("[[");
    line.remove_prefix(array ? 2 : 1);
    const std::size_t end = line.find(array ? "]]" : "]");
    return std::string(trimmed(line.substr(0, end)));
  }
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote != 0) {
      if (c == '\\' && quote == '"') ++i;  // an escaped character in a basic string
      else if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '=') {
      return std::string(trimmed(line.substr(0, i)));
    }
  }
  return {};
}

}  // namespace

std::string readable_parse_error(const toml::parse_error& error, std::string_view text) {
  const std::string description(error.description());
  if (description.find("cannot redefine existing") == std::string::npos) return description;
  const std::string name =
      defined_name(line_of(text, static_cast<std::size_t>(error.source().begin.line)));
  if (name.empty()) return description;
  const bool table = description.find("table header") != std::string::npos;
  std::string out(table ? "table [" : "key ");
  out.append(name).append(table ? "]" : "");
  out.append(" is defined twice (TOML allows each key and table once; remove or rename one)");
  return out;
}

}  // namespace stiction::scene
