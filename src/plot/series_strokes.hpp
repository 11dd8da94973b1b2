// The data of a panel: each series as pixels, and its drawing in its style. Where a series
// turns (reverses direction) more often than a line can show, a polyline would pile up into a
// block with moiré; there it is drawn as its envelope instead, as plotting libraries do for
// dense data: a band filled between the lowest and the highest value in each pixel column,
// its edges lined in the series' style inside the band, so the band's ink spans exactly the
// data's extremes. Sparse stretches stay polylines, drawn as before. Internal to src/plot.
#pragma once

#include <vector>

#include "plot/figure.hpp"
#include "plot/painter.hpp"
#include "plot/y_axis.hpp"

namespace stiction::plot {

// The series' samples as pixels (NaN where a sample cannot be placed: non-finite, or not
// positive on a log axis).
std::vector<Point> to_pixels(const Series& series, const Axis& x, const Axis& y);

// A series split into what is drawn: polylines, and bands where it is dense. A band is one
// entry per pixel column c (x from c to c + 1, clipped to the band's ends): its highest and
// lowest pixel y (top <= bottom), the samples and the line between them both counted.
struct BandColumn {
  double x0 = 0.0, x1 = 0.0;
  double top = 0.0, bottom = 0.0;
};
struct SeriesPiece {
  std::vector<Point> line;  // a polyline (empty for a band)
  std::vector<BandColumn> band;
};
// Dense: turning points (reversals of more than half a pixel) closer together than
// `spacing` pixels, at least four in a row; needs x non-decreasing (else all polylines).
// Non-finite points end a piece.
std::vector<SeriesPiece> split_dense(const std::vector<Point>& points, double spacing);

// The smallest distance between turning points that a line of `line_width` pixels shows:
// closer ones make a band.
double dense_spacing(double line_width);

// The opacity of a band's fill, as a share of its series' colour: light enough that two
// overlapping bands stay a light tint of both, not a grey block.
inline constexpr double kBandTint = 0.14;

// Every series of the panel in its style (series_style(index) unless it has its own),
// clipped to the frame, the dense pieces as bands whose fills go under every line; records
// each series drawn in the layout (when given).
void draw_series(Painter& painter, const Panel& panel,
                 const std::vector<std::vector<Point>>& pixels, const Rect& frame, double line,
                 FigureLayout* layout);

}  // namespace stiction::plot
