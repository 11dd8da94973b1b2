#include "plot/text_fit.hpp"

#include <algorithm>

namespace stiction::plot {
namespace {

// Byte offsets where UTF-8 code points start.
std::vector<std::size_t> code_point_starts(const std::string& s) {
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) starts.push_back(i);
  }
  return starts;
}

}  // namespace

std::string fit(Painter& painter, const std::string& text, double size, double max_width) {
  if (painter.measure(text, size).width <= max_width) return text;
  const std::vector<std::size_t> starts = code_point_starts(text);
  const int n = static_cast<int>(starts.size());
  auto shortened = [&](int keep) {
    const int head = (keep + 2) / 3, tail = keep - head;  // the end tells names apart more often
    return text.substr(0, head < n ? starts[head] : text.size()) + "\u2026" +
           text.substr(tail > 0 ? starts[n - tail] : text.size());
  };
  int lo = 0, hi = n - 1;  // largest `keep` that fits, by bisection
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (painter.measure(shortened(mid), size).width <= max_width) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return shortened(lo);
}

std::vector<std::string> wrap(Painter& painter, const std::string& text, double max_width,
                              double size, std::size_t max_lines) {
  if (painter.measure(text, size).width <= max_width) return {text};
  // Words end at spaces; a long name also breaks after '_' and '.' (the break is marked by
  // the character itself staying at the end of the line: "joint0_" / "friction.tau").
  std::vector<std::string> words;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  std::vector<std::string> pieces;
  for (const std::string& w : words) {
    if (w.front() == '[' || painter.measure(w, size).width <= max_width) {
      pieces.push_back(w);
      continue;
    }
    std::size_t from = 0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      if ((w[i] == '_' || w[i] == '.') && i + 1 < w.size()) {
        pieces.push_back(w.substr(from, i + 1 - from) + "\x01");  // \x01: no space after
        from = i + 1;
      }
    }
    pieces.push_back(w.substr(from));
  }
  words = std::move(pieces);
  // Keep "[...]" groups together.
  std::vector<std::string> groups;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (!groups.empty() && groups.back().front() == '[' && groups.back().back() != ']') {
      groups.back() += " " + words[i];
    } else {
      groups.push_back(words[i]);
    }
  }
  std::vector<std::string> lines;
  std::string current;
  auto joined = [](const std::string& a, const std::string& b) {
    if (a.empty()) return b;
    if (a.back() == '\x01') return a.substr(0, a.size() - 1) + b;
    return a + " " + b;
  };
  for (const std::string& g : groups) {
    const std::string candidate = joined(current, g);
    const bool unit = g.front() == '[';
    if (!current.empty() && (unit || painter.measure(candidate, size).width > max_width)) {
      lines.push_back(current);
      current = g;
    } else {
      current = candidate;
    }
  }
  if (!current.empty()) lines.push_back(current);
  // Too many lines: the unit line stays, the words before it join into one shortened line.
  if (lines.size() > max_lines && max_lines >= 2) {
    const bool unit_last = lines.back().front() == '[';
    std::string rest;
    const std::size_t keep = max_lines - (unit_last ? 2 : 1);  // lines kept as they are
    for (std::size_t i = keep; i + (unit_last ? 1 : 0) < lines.size(); ++i) {
      rest = joined(rest, lines[i]);
    }
    std::vector<std::string> merged(lines.begin(), lines.begin() + static_cast<long>(keep));
    merged.push_back(rest);
    if (unit_last) merged.push_back(lines.back());
    lines = std::move(merged);
  }
  for (std::string& line : lines) {
    if (!line.empty() && line.back() == '\x01') line.pop_back();
    std::erase(line, '\x01');
    line = fit(painter, line, size, max_width);
  }
  return lines;
}

}  // namespace stiction::plot
