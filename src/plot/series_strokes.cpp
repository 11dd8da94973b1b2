#include "plot/series_strokes.hpp"

#include <algorithm>
#include <cmath>

#include "plot/style.hpp"

namespace stiction::plot {
namespace {

// Reversals smaller than this (pixels) are not turning points: rounding noise in a flat
// signal does not make a band.
constexpr double kHysteresis = 0.5;
// A band needs at least this many turning points in a row.
constexpr int kMinTurns = 4;

// Indices of the turning points of y along points[begin, end): the extremes of a zigzag that
// reverses by more than kHysteresis.
std::vector<std::size_t> turning_points(const std::vector<Point>& p, std::size_t begin,
                                        std::size_t end) {
  std::vector<std::size_t> turns;
  if (end - begin < 3) return turns;
  int direction = 0;  // +1 rising y, -1 falling y, 0 not yet known
  std::size_t extreme = begin;
  for (std::size_t i = begin + 1; i < end; ++i) {
    const double dy = p[i].y - p[extreme].y;
    if (direction == 0) {
      if (std::abs(dy) > kHysteresis) direction = dy > 0 ? 1 : -1;
      if (direction != 0) extreme = i;
      continue;
    }
    if (dy * direction >= 0.0) {
      extreme = i;  // still going the same way: a new extreme
    } else if (std::abs(dy) > kHysteresis) {
      turns.push_back(extreme);
      direction = -direction;
      extreme = i;
    }
  }
  return turns;
}

// y of the segment a-b at x (a.x <= x <= b.x).
double at(Point a, Point b, double x) {
  if (b.x <= a.x) return a.y;
  return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
}

// The band of points[a..b] (x non-decreasing), one column per pixel.
std::vector<BandColumn> band_of(const std::vector<Point>& p, std::size_t a, std::size_t b,
                                long reach) {
  const double x_begin = p[a].x, x_end = p[b].x;
  const long c0 = static_cast<long>(std::floor(x_begin));
  const long c1 = static_cast<long>(std::floor(x_end));
  std::vector<BandColumn> columns;
  columns.reserve(static_cast<std::size_t>(c1 - c0 + 1));
  for (long c = c0; c <= c1; ++c) {
    BandColumn col;
    col.x0 = std::max(static_cast<double>(c), x_begin);
    col.x1 = std::min(static_cast<double>(c + 1), x_end);
    col.top = std::numeric_limits<double>::infinity();
    col.bottom = -std::numeric_limits<double>::infinity();
    columns.push_back(col);
  }
  auto include = [&](double x, double y) {
    const long c = std::clamp(static_cast<long>(std::floor(x)), c0, c1);
    BandColumn& col = columns[static_cast<std::size_t>(c - c0)];
    col.top = std::min(col.top, y);
    col.bottom = std::max(col.bottom, y);
  };
  for (std::size_t i = a; i <= b; ++i) {
    include(p[i].x, p[i].y);
    // The line to the next sample counts in every column it crosses: its value at each
    // column boundary belongs to both columns.
    if (i < b) {
      for (double edge = std::floor(p[i].x) + 1.0; edge <= p[i + 1].x; edge += 1.0) {
        const double y = at(p[i], p[i + 1], edge);
        include(edge - 0.5, y);
        include(edge + 0.5, y);
      }
    }
  }
  std::erase_if(columns, [](const BandColumn& c) { return !(c.top <= c.bottom) || c.x1 < c.x0; });
  // A column narrower than the oscillation holds only part of a swing: its own extremes
  // would make the band's edges zigzag (moiré again, in the edges). Each column takes the
  // extremes within `reach` columns either side, about one period of the oscillation.
  std::vector<BandColumn> widened = columns;
  const long n = static_cast<long>(columns.size());
  for (long i = 0; i < n; ++i) {
    for (long j = std::max(0L, i - reach); j <= std::min(n - 1, i + reach); ++j) {
      widened[i].top = std::min(widened[i].top, columns[j].top);
      widened[i].bottom = std::max(widened[i].bottom, columns[j].bottom);
    }
  }
  return widened;
}

}  // namespace

std::vector<Point> to_pixels(const Series& series, const Axis& x, const Axis& y) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  std::vector<Point> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) points.push_back({x.map(series.x[i]), y.map(series.y[i])});
  return points;
}

double dense_spacing(double line_width) { return std::max(3.0, 2.5 * line_width); }

std::vector<SeriesPiece> split_dense(const std::vector<Point>& points, double spacing) {
  std::vector<SeriesPiece> pieces;
  bool monotone = true;
  for (std::size_t i = 1; i < points.size() && monotone; ++i) {
    if (std::isfinite(points[i].x) && std::isfinite(points[i - 1].x) &&
        points[i].x < points[i - 1].x) {
      monotone = false;
    }
  }
  std::size_t begin = 0;
  while (begin < points.size()) {
    // A run of finite points [begin, end).
    while (begin < points.size() &&
           !(std::isfinite(points[begin].x) && std::isfinite(points[begin].y)))
      ++begin;
    std::size_t end = begin;
    while (end < points.size() && std::isfinite(points[end].x) && std::isfinite(points[end].y))
      ++end;
    if (begin == end) break;
    // Dense stretches: runs of turning points closer than `spacing`.
    std::vector<std::pair<std::size_t, std::size_t>> dense;
    if (monotone) {
      const std::vector<std::size_t> turns = turning_points(points, begin, end);
      std::size_t k = 0;
      while (k + 1 < turns.size()) {
        std::size_t j = k;
        while (j + 1 < turns.size() && points[turns[j + 1]].x - points[turns[j]].x < spacing) ++j;
        // The first and last swing of the run stay in the polylines: the step into and out
        // of the oscillation is drawn as the line it is, not as part of the band.
        if (static_cast<int>(j - k + 1) >= kMinTurns) dense.push_back({turns[k + 1], turns[j - 1]});
        k = std::max(j, k + 1);
      }
    }
    std::size_t from = begin;
    for (const auto& [a, b] : dense) {
      if (a > from) {
        pieces.push_back({std::vector<Point>(points.begin() + static_cast<long>(from),
                                             points.begin() + static_cast<long>(a) + 1),
                          {}});
      }
      pieces.push_back({{}, band_of(points, a, b, static_cast<long>(std::ceil(spacing)))});
      from = b;
    }
    if (end - from >= 1) {
      pieces.push_back({std::vector<Point>(points.begin() + static_cast<long>(from),
                                           points.begin() + static_cast<long>(end)),
                        {}});
    }
    begin = end;
  }
  return pieces;
}

void draw_series(Painter& painter, const Panel& panel,
                 const std::vector<std::vector<Point>>& pixels, const Rect& frame, double line,
                 FigureLayout* layout) {
  painter.clip(frame);
  std::vector<Stroke> strokes;
  std::vector<std::vector<SeriesPiece>> split;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    const Series& series = panel.series[i];
    const LineStyle style = series.style ? *series.style : series_style(static_cast<int>(i));
    strokes.push_back(make_stroke(style, line));
    split.push_back(split_dense(pixels[i], dense_spacing(strokes.back().width)));
  }
  // The bands' fills first, under every line: a band never tints another series' line, and
  // where two bands overlap their light tints stay light (each is kBandTint of its colour).
  for (std::size_t i = 0; i < split.size(); ++i) {
    for (const SeriesPiece& piece : split[i]) {
      if (piece.band.empty()) continue;
      std::vector<Point> outline;
      for (const BandColumn& c : piece.band) {
        outline.push_back({c.x0, c.top});
        outline.push_back({c.x1, c.top});
      }
      for (auto c = piece.band.rbegin(); c != piece.band.rend(); ++c) {
        outline.push_back({c->x1, c->bottom});
        outline.push_back({c->x0, c->bottom});
      }
      image::Rgba tint = strokes[i].colour;
      tint.a = static_cast<std::uint8_t>(tint.a * kBandTint);
      painter.fill_polygon(outline, tint);
    }
  }
  for (std::size_t i = 0; i < split.size(); ++i) {
    const Stroke& stroke = strokes[i];
    const std::vector<SeriesPiece>& pieces = split[i];
    const bool dense = std::any_of(pieces.begin(), pieces.end(),
                                   [](const SeriesPiece& p) { return !p.band.empty(); });
    if (!dense) {
      painter.polyline(pixels[i], stroke);  // sparse: exactly the polyline, gaps and all
    } else {
      for (const SeriesPiece& piece : pieces) {
        if (piece.band.empty()) {
          painter.polyline(piece.line, stroke);
          continue;
        }
        // The band's edges: its series' line inside its extremes, so its ink spans exactly
        // the lowest to the highest value.
        const double half = 0.5 * stroke.width;
        std::vector<Point> top, bottom;
        for (const BandColumn& c : piece.band) {
          const double mid = 0.5 * (c.x0 + c.x1);
          const double inset = std::min(half, 0.5 * (c.bottom - c.top));
          top.push_back({mid, c.top + inset});
          bottom.push_back({mid, c.bottom - inset});
        }
        painter.polyline(top, stroke);
        painter.polyline(bottom, stroke);
      }
    }
    const Series& series = panel.series[i];
    if (layout) layout->series.push_back(series.source.empty() ? series.label : series.source);
  }
  painter.unclip();
}

}  // namespace stiction::plot
