#include "scene/overrides.hpp"

#include <cctype>
#include <memory>
#include <vector>

#include "scene/toml_reader.hpp"
#include "scene/toml_shape.hpp"

namespace stiction::scene {
namespace {

constexpr std::size_t kMaxIndex = 1'000'000'000;

// One step of a key path: a table key, or an array index.
struct Step {
  std::string key;  // empty for an index
  std::size_t index = 0;
  int column = 1;   // 1-based column in the argument, for messages
  std::string path; // the key path up to and including this step
};

toml::source_region region(const std::shared_ptr<const std::string>& source, int column) {
  toml::source_region r;
  r.begin = {1, static_cast<toml::source_index>(column)};
  r.end = r.begin;
  r.path = source;
  return r;
}

std::vector<Step> parse_path(const std::string& key, const std::shared_ptr<const std::string>& source) {
  std::vector<Step> steps;
  std::size_t i = 0;
  std::string path;
  auto bad = [&](std::size_t at, const std::string& why) {
    return InputError::at(region(source, static_cast<int>(at) + 1), why);
  };
  while (i <= key.size()) {
    const std::size_t start = i;
    while (i < key.size() && key[i] != '.' && key[i] != '[') ++i;
    if (i == start) throw bad(start, "expected a key name in '" + key + "'");
    const std::string name = key.substr(start, i - start);
    for (char c : name) {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) {
        throw bad(start, "invalid key name '" + name + "' (bare TOML keys only)");
      }
    }
    path += (path.empty() ? "" : ".") + name;
    steps.push_back({name, 0, static_cast<int>(start) + 1, path});
    while (i < key.size() && key[i] == '[') {
      const std::size_t close = key.find(']', i);
      if (close == std::string::npos || close == i + 1) throw bad(i, "expected [INDEX] in '" + key + "'");
      std::size_t index = 0;
      for (std::size_t k = i + 1; k < close; ++k) {
        if (!std::isdigit(static_cast<unsigned char>(key[k]))) throw bad(k, "array index must be a number");
        // Stop before the index could wrap around (2^64 would become element 0): no scene
        // array comes near this many elements, so a larger index is out of range anyway.
        if (index > kMaxIndex / 10) throw bad(i + 1, "array index out of range in '" + key + "'");
        index = index * 10 + static_cast<std::size_t>(key[k] - '0');
      }
      path += key.substr(i, close + 1 - i);
      steps.push_back({"", index, static_cast<int>(i) + 1, path});
      i = close + 1;
    }
    if (i == key.size()) break;
    if (key[i] != '.') throw bad(i, "expected '.' or '[' in '" + key + "'");
    ++i;
    if (i == key.size()) throw bad(i, "key ends with '.'");
  }
  return steps;
}

// Top-level tables whose absence means all their defaults, exactly as an empty table does:
// `--set render.fps=10` on a scene without [render] creates it (it was "unknown key
// 'render'"). Components, plots and the overlay or inset are not created: an empty one is
// not the same as none.
bool is_table_of_defaults(const std::string& key) {
  return key == "simulation" || key == "render" || key == "camera" || key == "verify" ||
         key == "accuracy";
}

}  // namespace

void apply_override(toml::table& document, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError("--set " + assignment + ": error: expected KEY=VALUE");
  }
  const std::string key = assignment.substr(0, eq);
  const auto source = std::make_shared<const std::string>("--set " + key);
  const std::vector<Step> steps = parse_path(key, source);

  // Parse the value with a bare key of the same length in front of it, so that toml++
  // reports columns as they are in the user's argument.
  toml::table parsed;
  check_toml_shape(assignment.substr(eq + 1), *source);  // a deep dotted key overflows toml++
  try {
    parsed = toml::parse(std::string(eq, 'v') + assignment.substr(eq), std::string_view(*source));
  } catch (const toml::parse_error& e) {
    throw InputError::at(e.source(), key + ": invalid TOML value '" + assignment.substr(eq + 1) +
                                         "': " + std::string(e.description()));
  }
  toml::node* value = parsed.get(std::string(eq, 'v'));
  if (value == nullptr || parsed.size() != 1) {
    throw InputError::at(region(source, static_cast<int>(eq) + 2),
                         key + ": expected exactly one TOML value after '='");
  }

  // Walk to the container of the last step; everything on the way must exist.
  toml::node* current = &document;
  for (std::size_t s = 0; s + 1 < steps.size(); ++s) {
    const Step& step = steps[s];
    toml::node* next = nullptr;
    if (!step.key.empty()) {
      toml::table* t = current->as_table();
      if (t == nullptr) {
        throw InputError::at(region(source, step.column),
                             "unknown key '" + step.path + "' (its parent is not a table)");
      }
      next = t->get(step.key);
      if (next == nullptr && s == 0 && is_table_of_defaults(step.key)) {
        next = t->insert(toml::key(step.key, region(source, step.column)), toml::table{}).first->second.as_table();
      }
    } else {
      toml::array* a = current->as_array();
      if (a == nullptr) throw InputError::at(region(source, step.column), "'" + steps[s - 1].path + "' is not an array");
      if (step.index < a->size()) next = a->get(step.index);
      else throw InputError::at(region(source, step.column), "index out of range in '" + step.path + "'");
    }
    if (next == nullptr) throw InputError::at(region(source, step.column), "unknown key '" + step.path + "'");
    current = next;
  }

  const Step& last = steps.back();
  if (!last.key.empty()) {
    toml::table* t = current->as_table();
    if (t == nullptr) {
      throw InputError::at(region(source, last.column),
                           "unknown key '" + last.path + "' (its parent is not a table)");
    }
    // A new key keeps the argument as its position, so "unknown key" points there.
    if (t->contains(last.key)) {
      t->insert_or_assign(last.key, std::move(*value));
    } else {
      t->insert_or_assign(toml::key(last.key, region(source, 1)), std::move(*value));
    }
  } else {
    toml::array* a = current->as_array();
    if (a == nullptr) {
      throw InputError::at(region(source, last.column), "'" + steps[steps.size() - 2].path + "' is not an array");
    }
    if (last.index >= a->size()) {
      throw InputError::at(region(source, last.column), "index out of range in '" + last.path + "'");
    }
    a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(last.index), std::move(*value));
  }
}

}  // namespace stiction::scene
