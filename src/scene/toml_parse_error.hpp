// toml++'s parse error as a user can read it. Its message for a key or table defined twice
// garbles the name (toml++ 3.3: `"mass" = 1.0` twice reads "cannot redefine existing
// floating-point '"mamass" '", a table `[bodies."a.b"]` twice 'bodies."a.a.b"'): that one is
// rewritten with the name as the user wrote it, taken from the line of the scene's text.
#pragma once

#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace stiction::scene {

// "DESCRIPTION" of the error at `error`'s position in `text`, the document toml++ parsed.
std::string readable_parse_error(const toml::parse_error& error, std::string_view text);

}  // namespace stiction::scene
