// Text from files that the program echoes to the terminal (error messages quoting a key, a
// value, a URDF joint name or mesh file name): its control characters escaped, so that a
// file cannot move the cursor, retitle the window or hide text with escape sequences
// (issue 39). Newlines and tabs, which the program's own messages use, are kept.
#pragma once

#include <string>
#include <string_view>

namespace stiction::sys {

// C0 controls but '\n' and '\t', DEL and the C1 controls (U+0080..U+009F, as UTF-8) as
// "\xNN" (C1: "\u00NN"); everything else, UTF-8 included, unchanged.
std::string terminal_safe(std::string_view text);

}  // namespace stiction::sys
