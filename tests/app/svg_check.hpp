// A small SVG reader for tests: checks that a document is well-formed XML (one root element,
// every element closed in order, quoted attributes) and collects its <path> elements with
// their style and the vertices of their M/L commands, so a test can find a plotted series.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

namespace stiction::testing {

struct SvgPoint {
  double x = 0.0, y = 0.0;
};

struct SvgPath {
  std::string style;
  std::vector<SvgPoint> points;  // vertices of M and L commands; empty if it has curves
};

struct SvgDocument {
  bool well_formed = false;
  std::string error;  // why not, if not
  std::string root;   // name of the root element
  std::vector<SvgPath> paths;
};

namespace svg_detail {

// Value of attribute `name` in a tag's text, or "" if absent.
inline std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const std::size_t start = at + key.size();
  const std::size_t end = tag.find('"', start);
  return end == std::string::npos ? "" : tag.substr(start, end - start);
}

inline std::vector<SvgPoint> vertices(const std::string& d) {
  std::vector<SvgPoint> points;
  std::istringstream in(d);
  std::string command;
  while (in >> command) {
    if (command != "M" && command != "L") return {};  // curves, arcs, close: not a polyline
    SvgPoint p;
    if (!(in >> p.x >> p.y)) return {};
    points.push_back(p);
  }
  return points;
}

}  // namespace svg_detail

inline SvgDocument parse_svg(const std::string& text) {
  SvgDocument doc;
  std::vector<std::string> open;
  int roots = 0;
  std::size_t i = 0;
  auto fail = [&](const std::string& why) {
    doc.error = why + " at byte " + std::to_string(i);
    return doc;
  };
  while ((i = text.find('<', i)) != std::string::npos) {
    if (text.compare(i, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", i);
      if (end == std::string::npos) return fail("unclosed comment");
      i = end + 3;
      continue;
    }
    // The tag ends at the first '>' outside quotes.
    std::size_t j = i + 1;
    bool quoted = false;
    while (j < text.size() && (quoted || text[j] != '>')) {
      if (text[j] == '"') quoted = !quoted;
      ++j;
    }
    if (j >= text.size()) return fail("unclosed tag");
    const std::string tag = text.substr(i, j + 1 - i);
    i = j + 1;
    if (tag.compare(0, 2, "<?") == 0) continue;  // the XML declaration
    const bool closing = tag[1] == '/';
    const bool empty = tag[tag.size() - 2] == '/';
    std::size_t name_end = closing ? 2 : 1;
    while (name_end < tag.size() && tag[name_end] != ' ' && tag[name_end] != '>' &&
           tag[name_end] != '/' && tag[name_end] != '\n') {
      ++name_end;
    }
    const std::size_t name_start = closing ? 2 : 1;
    const std::string name = tag.substr(name_start, name_end - name_start);
    if (name.empty()) return fail("tag without a name");
    if (closing) {
      if (open.empty() || open.back() != name) return fail("</" + name + "> closes nothing open");
      open.pop_back();
      continue;
    }
    if (open.empty()) {
      if (++roots > 1) return fail("a second root element");
      doc.root = name;
    }
    if (name == "path") {
      doc.paths.push_back({svg_detail::attribute(tag, "style"),
                           svg_detail::vertices(svg_detail::attribute(tag, "d"))});
    }
    if (!empty) open.push_back(name);
  }
  if (!open.empty()) return fail("<" + open.back() + "> never closed");
  if (roots != 1) return fail("no root element");
  doc.well_formed = true;
  return doc;
}

}  // namespace stiction::testing
