// Figures for print: one or more panels stacked vertically and sharing a horizontal (time)
// axis, each with its own vertical axis (linear or log), light grid, 1-2-5 ticks with labels,
// an axis label with units and a legend; a title on top; vertical lines marking events.
//
//   plot::Figure figure;
//   figure.title = "Simulation I: sphere rolling with slip";
//   plot::Panel& v = figure.panels.emplace_back();
//   v.label = "Horizontal velocity"; v.unit = "m/s";
//   v.series.push_back({"centre", t, vx});
//   v.series.push_back({"contact point", t, slip});
//   figure.events.push_back({0.583, "stick, t = 0.583 s", "stick"});
//   image::Image png = plot::render(figure);                      // or
//   plot::write_figure(figure, "fig.pdf", plot::Format::pdf, 300);
//
// Everything is drawn by one code path through cairo (PNG, SVG and PDF alike), text with
// the bundled DejaVu Sans through cairo-ft, kerned (an SVG keeps it as <text> elements). The
// layout measures every text: y labels wrap or are shortened in the middle ("…"), tick
// labels that would touch are thinned (every vertical axis keeps two), a legend takes a
// place inside the axes with no data under it, else goes above the panel or beside the axes.
// A labelled event's label sits at its mark above the top panel (over it, beside it with a
// leader, or higher up); other events are light ticks. A series denser than a line can show
// is drawn as its min/max band. draw() reports every box it drew (FigureLayout).
//
// Series are told apart by colour (the Okabe-Ito colour-blind-safe palette) AND by dash
// pattern (solid, dashed, dotted, dash-dot, ...), so a figure printed in grey stays legible.
// Two designs of sizes: in pixels (fonts, line widths and margins designed for 1600x1000
// pixels, scaled with min(width/1600, height/1000)), or, when Figure::print is set, in points
// on a page of width_mm x height_mm: text of font_pt whatever the page size, lines of about
// 1 pt, a pixel size that is the page at its dpi (docs/plots.md, "How figures are drawn").
#pragma once

#include <cairo.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "plot/layout.hpp"
#include "text/font.hpp"

namespace stiction::plot {

struct LineStyle {
  image::Rgba colour{0, 0, 0, 255};
  // In line units: pixels at 1600x1000 in the pixel design, 0.3 pt in the print design.
  std::vector<double> dash;
  double width = 3.0;
};

// The style of the index-th series of a panel: colour and dash pattern both cycle, with
// different periods (7 colours, 5 patterns), so neighbours differ in both.
LineStyle series_style(int index);

struct Series {
  std::string label;  // legend text; an empty label keeps the series out of the legend
  std::vector<double> x;
  std::vector<double> y;           // non-finite values (and non-positive ones on a log axis) break
                                   // the line
  std::optional<LineStyle> style;  // default: series_style(index in the panel)
  std::string source{};  // where the data came from (a trajectory column), for the layout report
};

// A horizontal line at a fixed value, e.g. a friction level: thin, grey, dashed, and listed in
// the panel's legend under its label.
struct ReferenceLine {
  double y = 0.0;
  std::string label;
};

struct Panel {
  std::string label;  // vertical axis label, e.g. "Horizontal velocity"
  std::string unit;   // e.g. "m/s"; printed as "label [unit]"
  bool log = false;
  std::vector<Series> series;
  std::optional<double> y_min, y_max;     // fixed range instead of the data's
  std::vector<ReferenceLine> references;  // always inside the vertical range
  std::string caption{};  // a line above the panel, e.g. a long component name and what it is
  // Set by the layout (shared_legend_entries): the panel's other entries are in an earlier
  // panel's legend, so one entry left (a reference line) still gets a legend.
  bool legend_keeps_one_entry = false;
};

struct EventMarker {
  double x = 0.0;
  std::string label;  // printed at the mark above the top panel (when labelled)
  // "stick" (dashed grey), "slip" or "slide" (dash-dot red), another kind such as "tip",
  // "lift_off", "land" (dash-dot-dot ochre), "" (dashed grey)
  std::string kind{};
  // Important events are labelled at their marks (without overlapping each other); the rest
  // are drawn as unlabelled ticks (issue 21).
  bool labelled = true;
};

struct Figure {
  std::string title;
  std::string x_label = "Time t";
  std::string x_unit = "s";
  std::vector<Panel> panels;
  std::vector<EventMarker> events;
  std::optional<double> x_min, x_max;  // default: the range of the data
  int width = 1600;
  int height = 1000;
  // Physical size and type size (issue 21; the drawing code gives them their meaning): when
  // set, the figure is laid out for a page of width_mm x height_mm with text of font_pt
  // points, and its pixel size is that page at `dpi`.
  struct Print {
    double width_mm = 88.0;  // a one-column journal figure
    double height_mm = 66.0;
    double font_pt = 8.0;
    double dpi = 300.0;
  };
  std::optional<Print> print;
};

// Output formats of a figure file.
enum class Format { png, svg, pdf };
// "png", "svg", "pdf" (any case); nullopt for anything else.
std::optional<Format> parse_format(const std::string& name);
const char* extension(Format format);  // ".png", ".svg", ".pdf"

// The figure's size in pixels: its print page at the print dpi (rounded) when `print` is set,
// else width x height.
struct PixelSize {
  int width = 0, height = 0;
};
PixelSize pixel_size(const Figure& figure);

// Draws the figure with cairo into `cr`, whose user space is the figure's pixels (pixel_size;
// the caller scales for PDF). Returns the boxes drawn. Throws std::invalid_argument for a size
// below 200x150 or above 16384 pixels, text::FontError if the bundled font is missing.
FigureLayout draw(const Figure& figure, cairo_t* cr);

// Draws the figure on a white, opaque image of pixel_size(figure). A figure without
// panels, or panels without data, still gives axes (range [0, 1]) and never NaN positions.
image::Image render(const Figure& figure, FigureLayout* layout = nullptr);
// The same; `font` is not used (kept for callers that hold one: text goes through cairo).
image::Image render(const Figure& figure, text::Font& font);

// Writes the figure atomically as PNG (with its dpi in the pHYs chunk), SVG (user units =
// pixels) or PDF (vector). A print figure's page is width_mm x height_mm in every format (its
// own dpi; `dpi` is not used); otherwise the PNG carries `dpi`, the PDF page is width/dpi x
// height/dpi inches and the SVG is width x height px. Throws image::ImageError / io::IoError
// on a write failure.
FigureLayout write_figure(const Figure& figure, const std::filesystem::path& path, Format format,
                          double dpi = 100.0);

}  // namespace stiction::plot
