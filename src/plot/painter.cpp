#include "plot/painter.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stiction::plot {

Painter::Painter(cairo_t* cr, const CairoFont& font, FigureLayout& layout,
                 std::vector<PlacedText>* deferred)
    : cr_(cr), font_(font), layout_(layout), deferred_(deferred) {
  cairo_set_font_face(cr_, font.face());
  cairo_font_options_t* options = cairo_font_options_create();
  // How glyphs are rendered where they are drawn; where they go is measure()'s alone.
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_SLIGHT);
  cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
  cairo_set_font_options(cr_, options);
  cairo_font_options_destroy(options);
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  // The measuring font's options, complete: nothing left for a surface to decide.
  measure_options_ = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(measure_options_, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(measure_options_, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_antialias(measure_options_, CAIRO_ANTIALIAS_GRAY);
  cairo_font_options_set_subpixel_order(measure_options_, CAIRO_SUBPIXEL_ORDER_DEFAULT);
}

Painter::~Painter() {
  for (auto& [size, font] : measuring_) cairo_scaled_font_destroy(font);
  cairo_font_options_destroy(measure_options_);
}

cairo_scaled_font_t* Painter::measuring_font(double size) {
  for (const auto& [s, font] : measuring_) {
    if (s == size) return font;
  }
  cairo_matrix_t font_matrix, identity;
  cairo_matrix_init_scale(&font_matrix, size, size);
  cairo_matrix_init_identity(&identity);
  cairo_scaled_font_t* font =
      cairo_scaled_font_create(font_.face(), &font_matrix, &identity, measure_options_);
  measuring_.emplace_back(size, font);
  return font;
}

struct Painter::Glyphs {
  cairo_glyph_t* glyphs = nullptr;
  int count = 0;
  cairo_text_cluster_t* clusters = nullptr;  // for text extraction from a PDF
  int cluster_count = 0;
  cairo_text_cluster_flags_t flags{};
  Glyphs() = default;
  Glyphs(const Glyphs&) = delete;
  Glyphs& operator=(const Glyphs&) = delete;
  Glyphs(Glyphs&& o) noexcept { *this = std::move(o); }
  Glyphs& operator=(Glyphs&& o) noexcept {
    std::swap(glyphs, o.glyphs);
    std::swap(count, o.count);
    std::swap(clusters, o.clusters);
    std::swap(cluster_count, o.cluster_count);
    std::swap(flags, o.flags);
    return *this;
  }
  ~Glyphs() {
    cairo_glyph_free(glyphs);
    cairo_text_cluster_free(clusters);
  }
};

Painter::Glyphs Painter::shape(const std::string& text, double size) {
  Glyphs g;
  cairo_scaled_font_t* font = measuring_font(size);
  if (cairo_scaled_font_text_to_glyphs(font, 0.0, 0.0, text.c_str(), static_cast<int>(text.size()),
                                       &g.glyphs, &g.count, &g.clusters, &g.cluster_count,
                                       &g.flags) != CAIRO_STATUS_SUCCESS) {
    return Glyphs{};
  }
  double shift = 0.0;
  for (int i = 1; i < g.count; ++i) {
    shift += size * font_.kerning(g.glyphs[i - 1].index, g.glyphs[i].index);
    g.glyphs[i].x += shift;
  }
  return g;
}

Extent Painter::measure(const std::string& text, double size) {
  cairo_scaled_font_t* scaled = measuring_font(size);
  cairo_font_extents_t font;
  cairo_scaled_font_extents(scaled, &font);
  const Glyphs g = shape(text, size);
  cairo_text_extents_t ink{};
  if (g.count > 0) cairo_scaled_font_glyph_extents(scaled, g.glyphs, g.count, &ink);
  // x_advance: from the first glyph's origin to the pen after the last, kerning included.
  return {ink.x_advance, -ink.y_bearing, font.ascent, font.descent};
}

Rect Painter::text(const std::string& s, double x, double baseline, double size, image::Rgba colour,
                   TextRole role, int panel, bool rotated, const TextOrigin* origin) {
  const Extent e = measure(s, size);
  if (deferred_) {
    deferred_->push_back({s, x, baseline, size, colour, rotated});
  } else {
    set_colour(colour);
    cairo_save(cr_);
    cairo_translate(cr_, x, baseline);
    if (rotated) cairo_rotate(cr_, -0.5 * std::acos(-1.0));
    cairo_set_font_size(cr_, size);
    const Glyphs g = shape(s, size);
    cairo_show_text_glyphs(cr_, s.c_str(), static_cast<int>(s.size()), g.glyphs, g.count,
                           g.clusters, g.cluster_count, g.flags);
    cairo_new_path(cr_);
    cairo_restore(cr_);
  }
  const Rect box = rotated
                       ? Rect{x - e.line_ascent, baseline - e.width, x + e.line_descent, baseline}
                       : Rect{x, baseline - e.line_ascent, x + e.width, baseline + e.line_descent};
  layout_.texts.push_back(
      {s, role, box, panel, origin ? origin->given : s, origin ? origin->shortened : false});
  return box;
}

// Stroked in pieces of at most kPiece segments: cairo's stroker holds the polygon of the
// whole path it strokes, and a dense series that swings across its panel (a quaternion
// over a long run) took over 100 MB in one stroke. Each piece starts where the last one
// ended, its dash pattern carried on (cairo restarts the pattern at every sub-path).
//
// A point with no finite neighbour (a series of one point, or one between two gaps) makes no
// segment, so cairo would draw nothing: it gets a dot three line widths across instead, or
// it would vanish from the figure while its legend entry stays.
void Painter::polyline(const std::vector<Point>& points, const Stroke& stroke) {
  constexpr int kPiece = 512;
  apply(stroke);
  bool open = false;
  int segments = 0;
  double along = 0.0;  // length since the sub-path began, for the dash offset
  Point last{};
  std::vector<Point> isolated;
  int in_path = 0;  // points in the current sub-path
  for (const Point& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      if (in_path == 1) isolated.push_back(last);
      open = false;
      in_path = 0;
      continue;
    }
    ++in_path;
    if (!open) {
      cairo_move_to(cr_, p.x, p.y);
      open = true;
      along = 0.0;
    } else {
      cairo_line_to(cr_, p.x, p.y);
      along += std::hypot(p.x - last.x, p.y - last.y);
      if (++segments == kPiece) {
        cairo_stroke(cr_);
        segments = 0;
        set_dash_offset(stroke, along);
        cairo_move_to(cr_, p.x, p.y);
      }
    }
    last = p;
  }
  if (in_path == 1) isolated.push_back(last);
  cairo_stroke(cr_);
  for (const Point& p : isolated) {
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, p.x, p.y, 1.5 * stroke.width, 0.0, 2.0 * M_PI);
  }
  if (!isolated.empty()) cairo_fill(cr_);
}

void Painter::fill_rect(const Rect& r, image::Rgba colour) {
  cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
  set_colour(colour);
  cairo_fill(cr_);
}

void Painter::fill_polygon(const std::vector<Point>& points, image::Rgba colour) {
  if (points.size() < 3) return;
  cairo_move_to(cr_, points[0].x, points[0].y);
  for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr_, points[i].x, points[i].y);
  cairo_close_path(cr_);
  set_colour(colour);
  cairo_fill(cr_);
}

void Painter::stroke_rect(const Rect& r, const Stroke& stroke) {
  cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
  apply(stroke);
  cairo_stroke(cr_);
}

void Painter::clip(const Rect& r) {
  cairo_save(cr_);
  cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
  cairo_clip(cr_);
}

void Painter::unclip() { cairo_restore(cr_); }

void Painter::set_colour(image::Rgba c) {
  cairo_set_source_rgba(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
}

void Painter::apply(const Stroke& stroke) {
  set_colour(stroke.colour);
  cairo_set_line_width(cr_, stroke.width);
  set_dash_offset(stroke, 0.0);
}

void Painter::set_dash_offset(const Stroke& stroke, double offset) {
  // A dot is an "on" length of zero with round caps; cairo drops such pieces between
  // longer dashes, so they get a length too small to see.
  std::vector<double> dash = stroke.dash;
  for (std::size_t i = 0; i < dash.size(); i += 2) dash[i] = std::max(dash[i], 0.01);
  cairo_set_dash(cr_, dash.empty() ? nullptr : dash.data(), static_cast<int>(dash.size()), offset);
}

}  // namespace stiction::plot
