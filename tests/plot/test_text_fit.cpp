// The text rule (plot/text_fit.hpp), directly: wrapped at word boundaries, smaller down to
// its floor, then shortened by whole words (remarks first, then from the middle), the unit
// kept, a word never cut; and on generated phrases and widths, every word drawn is a whole
// word of the text.
#include <cairo.h>

#include <catch2/catch.hpp>
#include <cctype>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "plot/cairo_font.hpp"
#include "plot/text_fit.hpp"
#include "word_runs.hpp"

using namespace stiction;
using plot::fit_text;
using plot::FittedText;
using plot::TextRule;

using stiction::testing::word_runs;

namespace {

// A painter on a small image surface (text is only measured).
struct Measuring {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface{
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 16, 16), &cairo_surface_destroy};
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr{cairo_create(surface.get()),
                                                        &cairo_destroy};
  plot::CairoFont font = plot::CairoFont::open_default();
  plot::FigureLayout layout;
  plot::Painter painter{cr.get(), font, layout};
  double width(const std::string& s, double size) { return painter.measure(s, size).width; }
};

bool whole_words(const FittedText& fitted, const std::string& original) {
  const std::vector<std::string> given = word_runs(original);
  const std::set<std::string> words(given.begin(), given.end());
  for (const std::string& line : fitted.lines) {
    for (const std::string& w : word_runs(line)) {
      if (words.count(w) == 0) return false;
    }
  }
  return true;
}

const std::string kEllipsis = "\u2026";

}  // namespace

TEST_CASE("a text that fits is left alone", "[plot][text-fit]") {
  Measuring m;
  const FittedText f = fit_text(m.painter, "Velocity [m/s]", TextRule{30.0, 21.0, 1000.0, 3});
  CHECK(f.lines == std::vector<std::string>{"Velocity [m/s]"});
  CHECK(f.size == 30.0);
  CHECK_FALSE(f.shortened);
  CHECK_FALSE(f.below_floor);
}

TEST_CASE("a text wraps at spaces, its unit on a line of its own", "[plot][text-fit]") {
  Measuring m;
  const std::string text = "Horizontal velocity of the centre [m/s]";
  const double width = m.width("Horizontal velocity", 30.0) + 1.0;
  const FittedText f = fit_text(m.painter, text, TextRule{30.0, 21.0, width, 4});
  CHECK(f.lines == std::vector<std::string>{"Horizontal velocity", "of the centre", "[m/s]"});
  CHECK(f.size == 30.0);
  for (const std::string& line : f.lines) CHECK(m.width(line, f.size) <= width);
}

TEST_CASE("a long name breaks after '_' and a name's '.', never in a number", "[plot][text-fit]") {
  Measuring m;
  const std::string text = "joint0_friction.tau at 4.651 s";
  const double width = m.width("joint0_friction.", 30.0) + 1.0;
  const FittedText f = fit_text(m.painter, text, TextRule{30.0, 30.0, width, 4});
  REQUIRE_FALSE(f.shortened);
  CHECK(f.lines.front() == "joint0_friction.");
  for (const std::string& line : f.lines) {
    const bool number_whole =
        line.find("4.") == std::string::npos || line.find("4.651") != std::string::npos;
    CHECK(number_whole);
  }
  CHECK(whole_words(f, text));
}

TEST_CASE("a text shrinks down to its floor before it is shortened", "[plot][text-fit]") {
  Measuring m;
  const std::string text = "contact point of the sphere";
  const double full = m.width(text, 30.0);
  const FittedText f = fit_text(m.painter, text, TextRule{30.0, 21.0, 0.85 * full, 1});
  CHECK(f.lines == std::vector<std::string>{text});
  CHECK(f.size < 30.0);
  CHECK(f.size >= 21.0);
  CHECK_FALSE(f.shortened);
}

TEST_CASE("shortened: a remark first, then whole words from the middle, the unit kept",
          "[plot][text-fit]") {
  Measuring m;
  {
    const std::string text = "Key-signal error (relative)";
    const double width = m.width("Key-signal error", 21.0) + 1.0;
    const FittedText f = fit_text(m.painter, text, TextRule{30.0, 21.0, width, 1});
    CHECK(f.lines == std::vector<std::string>{"Key-signal error"});
    CHECK(f.size == 21.0);
    CHECK(f.shortened);
  }
  {
    const std::string text = "Horizontal velocity of the centre of the sphere [m/s]";
    const double width = m.width("Horizontal \u2026 the sphere [m/s]", 21.0) + 1.0;
    const FittedText f = fit_text(m.painter, text, TextRule{30.0, 21.0, width, 1});
    CHECK(f.lines == std::vector<std::string>{"Horizontal \u2026 the sphere [m/s]"});
    CHECK(f.shortened);
    CHECK(f.size == 21.0);
    CHECK(whole_words(f, text));
    // Narrower still: the last word and the unit.
    const FittedText g = fit_text(m.painter, text, TextRule{30.0, 21.0, 0.3 * width, 1});
    CHECK(g.lines == std::vector<std::string>{"\u2026 sphere [m/s]"});
  }
  {
    // An event label: the name's segments give way before the kind and the time.
    const std::string text = "joint1_friction stop 4.651 s";
    const double width = m.width("joint1_\u2026 stop 4.651 s", 30.0) + 1.0;
    const FittedText f = fit_text(m.painter, text, TextRule{30.0, 30.0, width, 1});
    CHECK(f.lines == std::vector<std::string>{"joint1_\u2026 stop 4.651 s"});
  }
}

TEST_CASE("a word that fits nowhere is set smaller, never cut", "[plot][text-fit]") {
  Measuring m;
  const double width = 0.5 * m.width("Velocity", 21.0);
  const FittedText f = fit_text(m.painter, "Velocity", TextRule{30.0, 21.0, width, 3});
  CHECK(f.lines == std::vector<std::string>{"Velocity"});
  CHECK(f.below_floor);
  CHECK(f.size < 21.0);
  CHECK(m.width("Velocity", f.size) <= width);
}

TEST_CASE("generated phrases: whole words, the unit kept, within the width", "[plot][text-fit]") {
  Measuring m;
  const std::vector<std::string> words{
      "horizontal", "velocity", "of",    "the",   "centre", "joint0_friction.tau", "sphere.v.x",
      "relative",   "(worst",   "case)", "4.651", "s",      "a_very_long_name"};
  std::mt19937 rng(5);
  auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  int shortened = 0, below = 0;
  for (int k = 0; k < 400; ++k) {
    std::string text;
    for (int i = 0; i <= pick(9); ++i) text += (i ? " " : "") + words[pick(13)];
    const bool unit = pick(2) == 0;
    if (unit) text += " [N\u00B7m]";
    const double size = 20.0 + pick(20);
    const TextRule rule{size, 0.75 * size, 20.0 + pick(600), static_cast<std::size_t>(1 + pick(4))};
    const FittedText f = fit_text(m.painter, text, rule);
    INFO(text << " -> " << f.joined() << " (width " << rule.max_width << ", " << rule.max_lines
              << " lines)");
    REQUIRE(!f.lines.empty());
    CHECK(f.lines.size() <= rule.max_lines);
    CHECK(whole_words(f, text));
    if (unit) CHECK(f.joined().find("[N\u00B7m]") != std::string::npos);
    CHECK(f.size <= size);
    if (!f.below_floor) {
      CHECK(f.size >= rule.min_size);
      for (const std::string& line : f.lines) CHECK(m.width(line, f.size) <= rule.max_width);
    }
    shortened += f.shortened ? 1 : 0;
    below += f.below_floor ? 1 : 0;
  }
  CHECK(shortened > 50);  // the cases reach every step
  CHECK(below > 5);
}
