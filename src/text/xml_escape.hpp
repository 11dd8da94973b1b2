// Text for XML and HTML documents the program writes (SVG figures, verify's reports).
#pragma once

#include <string>

namespace stiction::text {

// `text` with & < > " ' as entities and the control characters XML 1.0 forbids (all below
// 0x20 but tab, newline, return) as spaces: safe in element text and in quoted attributes.
std::string xml_escaped(const std::string& text);

}  // namespace stiction::text
