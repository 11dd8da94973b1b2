#include "plot/text_fit.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

namespace stiction::plot {
namespace {

const char* const kEllipsis = "\u2026";

// How a piece follows the previous one: after a space where a line may break; directly (a
// name's next segment); after a space inside parentheses ("θ(5 s)"); or after a space where
// no line breaks ("…" and the word after it). Lines break at the first kind; at the second
// and third only inside a group longer than a line.
enum class Join { space, none, in_parentheses, no_break };

// A piece of the text that is never broken: a word, a segment of a long name, or the unit.
struct Piece {
  std::string text;
  Join join = Join::space;
  bool unit = false;  // the bracketed unit at the end
};

// What shortening keeps or leaves out as a whole: a word, a name segment or a remark.
struct Atom {
  std::size_t first = 0, end = 0;  // its pieces, [first, end)
  bool remark = false;             // "(...)": left out first, without "…"
};

struct Parsed {
  std::vector<Piece> pieces;
  std::vector<Atom> atoms;  // every piece but the unit is in exactly one, in order
};

bool letter(unsigned char c) { return std::isalpha(c) != 0 || c >= 0x80; }

// A word's segments: it breaks after '_', after a '.' when its segment so far has a letter
// (a name's dot, not a decimal point) and after a hyphen between letters; each break keeps
// its character at the end of the segment ("joint0_" "friction.tau" reads as the name).
std::vector<std::string> segments(const std::string& word) {
  std::vector<std::string> out;
  std::size_t from = 0;
  bool has_letter = false;
  for (std::size_t i = 0; i + 1 < word.size(); ++i) {
    const auto c = static_cast<unsigned char>(word[i]);
    if (letter(c)) has_letter = true;
    const bool after = (c == '_') || (c == '.' && has_letter && word[i + 1] != '.') ||
                       (c == '-' && i > 0 && letter(static_cast<unsigned char>(word[i - 1])) &&
                        letter(static_cast<unsigned char>(word[i + 1])));
    if (after) {
      out.push_back(word.substr(from, i + 1 - from));
      from = i + 1;
      has_letter = false;
    }
  }
  out.push_back(word.substr(from));
  return out;
}

std::string join(const std::vector<std::string>& words, std::size_t from, std::size_t end) {
  std::string s;
  for (std::size_t i = from; i < end; ++i) s += (i > from ? " " : "") + words[i];
  return s;
}

Parsed parse(const std::string& text) {
  std::vector<std::string> words;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  // The unit: a bracket group that ends the text.
  std::size_t unit_from = words.size();
  if (!words.empty() && words.back().back() == ']') {
    for (std::size_t k = words.size(); k-- > 0;) {
      if (words[k].front() == '[') {
        unit_from = k;
        break;
      }
    }
  }
  Parsed p;
  auto closing = [&](std::size_t from, char close) {
    for (std::size_t j = from; j < unit_from; ++j) {
      if (words[j].find(close) != std::string::npos) return j;
    }
    return std::string::npos;
  };
  // Parentheses open before each word: a space inside them keeps its group on one line.
  std::vector<int> depth(words.size() + 1, 0);
  for (std::size_t i = 0; i < words.size(); ++i) {
    depth[i + 1] = depth[i];
    for (char c : words[i]) depth[i + 1] += c == '(' ? 1 : c == ')' ? -1 : 0;
    depth[i + 1] = std::max(0, depth[i + 1]);
  }
  auto word_join = [&](std::size_t i) { return depth[i] > 0 ? Join::in_parentheses : Join::space; };
  for (std::size_t i = 0; i < unit_from;) {
    Atom atom;
    atom.first = p.pieces.size();
    const std::size_t bracket = words[i].front() == '[' ? closing(i, ']') : std::string::npos;
    const std::size_t paren = words[i].front() == '(' ? closing(i, ')') : std::string::npos;
    if (bracket != std::string::npos) {  // a bracket group inside the text: one piece
      p.pieces.push_back({join(words, i, bracket + 1), Join::space, false});
      i = bracket + 1;
    } else {
      // A remark's words (each broken like any word) or one word.
      const std::size_t last = paren != std::string::npos ? paren : i;
      atom.remark = paren != std::string::npos;
      for (; i <= last; ++i) {
        const std::vector<std::string> parts = segments(words[i]);
        for (std::size_t k = 0; k < parts.size(); ++k) {
          p.pieces.push_back({parts[k], k > 0 ? Join::none : word_join(i), false});
          if (!atom.remark && k + 1 < parts.size()) {  // a name: each segment its own atom
            atom.end = p.pieces.size();
            p.atoms.push_back(atom);
            atom = Atom{p.pieces.size(), 0, false};
          }
        }
      }
    }
    atom.end = p.pieces.size();
    p.atoms.push_back(atom);
  }
  if (unit_from < words.size()) {
    p.pieces.push_back({join(words, unit_from, words.size()), Join::space, true});
  }
  return p;
}

// The pieces of the atoms kept (and the unit); a run of left-out atoms becomes one "…",
// unless it is remarks alone.
std::vector<Piece> kept(const Parsed& p, const std::vector<bool>& keep) {
  std::vector<Piece> out;
  for (std::size_t a = 0; a < p.atoms.size();) {
    if (keep[a]) {
      for (std::size_t i = p.atoms[a].first; i < p.atoms[a].end; ++i) out.push_back(p.pieces[i]);
      ++a;
      continue;
    }
    std::size_t b = a;
    bool only_remarks = true;
    for (; b < p.atoms.size() && !keep[b]; ++b) only_remarks = only_remarks && p.atoms[b].remark;
    if (!only_remarks) {
      out.push_back({kEllipsis, p.pieces[p.atoms[a].first].join, false});
      // The word after "…" stays on its line: a line of "…" alone says nothing.
      if (b < p.atoms.size() && keep[b]) {
        Piece next = p.pieces[p.atoms[b].first];
        if (next.join == Join::space) next.join = Join::no_break;
        for (std::size_t i = p.atoms[b].first; i < p.atoms[b].end; ++i) {
          out.push_back(i == p.atoms[b].first ? next : p.pieces[i]);
        }
        ++b;
      }
    }
    a = b;
  }
  if (!p.pieces.empty() && p.pieces.back().unit) out.push_back(p.pieces.back());
  if (!out.empty()) out.front().join = Join::space;
  return out;
}

std::string joined(const std::vector<Piece>& pieces, std::size_t from, std::size_t end) {
  std::string s;
  for (std::size_t i = from; i < end; ++i) {
    if (i > from && pieces[i].join != Join::none) s += ' ';
    s += pieces[i].text;
  }
  return s;
}

// The pieces on at most max_lines lines of at most `width`: the whole on one line if it fits;
// else word by word (a word: pieces glued together), a word longer than a line piece by
// piece, the unit on a line of its own. None when a piece alone is too wide or the lines are
// too many.
std::optional<std::vector<std::string>> wrap(Painter& painter, const std::vector<Piece>& pieces,
                                             double size, double width, std::size_t max_lines) {
  auto fits = [&](const std::string& s) { return painter.measure(s, size).width <= width; };
  const std::string whole = joined(pieces, 0, pieces.size());
  if (fits(whole)) return std::vector<std::string>{whole};
  if (max_lines <= 1) return std::nullopt;
  std::vector<std::string> lines;
  std::string current;
  for (std::size_t w = 0; w < pieces.size();) {
    std::size_t end = w + 1;
    while (end < pieces.size() && pieces[end].join != Join::space) ++end;
    const std::string word = joined(pieces, w, end);
    if (pieces[w].unit) {
      if (!current.empty()) lines.push_back(current);
      if (!fits(word)) return std::nullopt;
      current = word;
    } else if (fits(current.empty() ? word : current + " " + word)) {
      current = current.empty() ? word : current + " " + word;
    } else if (fits(word)) {
      lines.push_back(current);
      current = word;
    } else {
      for (std::size_t i = w; i < end; ++i) {
        const std::string glue =
            current.empty() || pieces[i].join == Join::none ? "" : std::string(" ");
        if (fits(current + glue + pieces[i].text)) {
          current += glue + pieces[i].text;
          continue;
        }
        if (!fits(pieces[i].text)) return std::nullopt;
        if (!current.empty()) lines.push_back(current);
        current = pieces[i].text;
      }
    }
    w = end;
  }
  if (!current.empty()) lines.push_back(current);
  if (lines.size() > max_lines) return std::nullopt;
  return lines;
}

}  // namespace

std::string FittedText::joined() const {
  std::string s;
  for (std::size_t i = 0; i < lines.size(); ++i) s += (i ? " " : "") + lines[i];
  return s;
}

FittedText fit_text(Painter& painter, const std::string& text, const TextRule& rule) {
  const Parsed p = parse(text);
  if (p.pieces.empty()) return FittedText{{text}, rule.size, false, false};
  const std::size_t lines = std::max<std::size_t>(1, rule.max_lines);
  const double floor = rule.min_size > 0.0 ? std::min(rule.min_size, rule.size) : rule.size;
  std::vector<bool> keep(p.atoms.size(), true);
  // 1, 2: whole, at its size, then smaller down to the floor.
  for (double size = rule.size;; size = std::max(floor, 0.9 * size)) {
    if (auto l = wrap(painter, kept(p, keep), size, rule.max_width, lines)) {
      return FittedText{*l, size, false, false};
    }
    if (size <= floor) break;
  }
  // 3: at the floor, remarks left out (the last first), then words from the middle.
  auto attempt = [&](const std::vector<bool>& k) {
    return wrap(painter, kept(p, k), floor, rule.max_width, lines);
  };
  for (std::size_t a = p.atoms.size(); a-- > 0;) {
    if (!p.atoms[a].remark) continue;
    keep[a] = false;
    if (auto l = attempt(keep)) return FittedText{*l, floor, true, false};
  }
  std::vector<std::size_t> rest;
  for (std::size_t a = 0; a < p.atoms.size(); ++a) {
    if (keep[a]) rest.push_back(a);
  }
  const std::size_t n = rest.size();
  std::vector<bool> shortest = keep;
  for (std::size_t k = n; k-- > 1;) {  // k atoms kept, h of them from the beginning
    // While two or more are kept, the first and the last stay.
    const long lo = k >= 2 ? 1 : 0, hi = k >= 2 ? static_cast<long>(k) - 1 : 0;
    const long preferred = std::clamp(std::lround(static_cast<double>(k) / 3.0), lo, hi);
    for (long h : {preferred, preferred - 1, preferred + 1}) {
      if (h < lo || h > hi) continue;
      std::vector<bool> trial = keep;
      for (std::size_t i = static_cast<std::size_t>(h); i < n - (k - static_cast<std::size_t>(h));
           ++i) {
        trial[rest[i]] = false;
      }
      if (auto l = attempt(trial)) return FittedText{*l, floor, true, false};
      if (k == 1 && h == preferred) shortest = trial;
    }
  }
  // 4: the shortest form, smaller than the floor: never cut.
  const bool shortened = shortest != std::vector<bool>(p.atoms.size(), true);
  for (double size = 0.9 * floor; size > 0.5; size *= 0.9) {
    if (auto l = wrap(painter, kept(p, shortest), size, rule.max_width, lines)) {
      return FittedText{*l, size, shortened, true};
    }
  }
  return FittedText{{joined(kept(p, shortest), 0, kept(p, shortest).size())}, 0.5, shortened, true};
}

}  // namespace stiction::plot
