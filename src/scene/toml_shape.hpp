// Bounds on the shape of a TOML text, checked before toml++ parses it. toml++ limits the
// nesting of values (256) but not the parts of a dotted key: `a.a.a...a = 1` with 30000 parts
// (60 kB) builds 30000 nested tables recursively and overflows the stack (SIGSEGV, issue 25).
// A scene needs a handful of parts and a few levels of arrays, so the bounds are far above
// any real scene and far below what the stack holds.
#pragma once

#include <string>

namespace stiction::scene {

struct TomlShapeLimits {
  static constexpr int kMaxKeyParts = 64;  // parts of one dotted key or table header
  static constexpr int kMaxNesting = 64;   // open [ and { at once (arrays, inline tables)
};

// Throws InputError "ORIGIN:LINE:COL: error: ..." at the first place `text` passes a bound.
// Strings and comments are skipped; a float's '.' counts as a key part, which is harmless.
void check_toml_shape(const std::string& text, const std::string& origin);

}  // namespace stiction::scene
