// `--set KEY=VALUE` (DESIGN section 3): KEY is a dotted path into the scene document
// (array elements as `name[i]`), VALUE a TOML value. The value replaces or adds one entry;
// whether the key is valid is decided by the loader's schema (TableReader::finish), so an
// override is checked exactly like a value written in the file. Positions in messages are
// "--set KEY:1:COL", COL counted in the argument "KEY=VALUE".
#pragma once

#include <string>

#include <toml++/toml.h>

namespace stiction::scene {

// Applies one "KEY=VALUE" to `document`; InputError on a malformed argument, a value that
// is not TOML, or a path through something that is not a table or array.
void apply_override(toml::table& document, const std::string& assignment);

}  // namespace stiction::scene
