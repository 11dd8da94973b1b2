// What a drawn figure reports about itself, so tests (and callers) can check that its text
// never overlaps and stays inside the image: every text box, legend box and panel frame, in
// pixels of the figure (x right, y down, origin top-left), and which series were drawn.
#pragma once

#include <string>
#include <vector>

namespace stiction::plot {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

// An axis-aligned rectangle in pixels (x0 <= x1, y0 <= y1; y down).
struct Rect {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool overlaps(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool inside(const Rect& o) const { return x0 >= o.x0 && y0 >= o.y0 && x1 <= o.x1 && y1 <= o.y1; }
};

enum class TextRole { title, axis_label, tick_label, legend_entry, event_label, note };

struct TextBox {
  std::string text;
  TextRole role = TextRole::note;
  Rect box;        // the logical box: advance width by the font's ascent + descent
  int panel = -1;  // the panel it belongs to (-1: the figure)
  // What the figure was given to say here (the whole title, axis title, legend entry, event
  // label; a wrapped text's lines each carry all of it), and whether the text rule left
  // words of it out (text_fit.hpp): `text` is then its whole words and segments with "…" in
  // place of those left out, never a piece of a word.
  std::string given;
  bool shortened = false;
};

// A labelled event: its mark (on the upper edge of the top panel), its label (an index into
// FigureLayout::texts; -1 when there was no room for it, even shortened, in any row: reported
// here, never dropped silently) and the leader drawn from the mark to a label that does not
// sit over its mark (a polyline from `mark` to the label's edge; empty when there is none).
struct EventLabelReport {
  int event = -1;  // index in Figure::events
  Point mark;
  int text = -1;
  std::vector<Point> leader;
};

// An axis as drawn: the data values at the ends of a frame (lo at its left or bottom edge);
// on a log axis the values are mapped by their logarithm.
struct AxisRange {
  double lo = 0.0, hi = 1.0;
  bool log = false;
};

struct FigureLayout {
  int width = 0, height = 0;
  std::vector<TextBox> texts;
  std::vector<Rect> panels;          // axes frames
  std::vector<Rect> legends;         // legend boxes (their entries are in `texts`)
  std::vector<bool> legend_outside;  // per legend: placed outside the axes (above or beside)
  std::vector<int> legend_panels;    // per legend: the panel it belongs to
  // Per legend: pixels of data (series and reference lines, as drawn) under its box and a
  // margin around it: at most plot::kLegendDataShare of its panel's data for a legend inside,
  // unless it found no room outside the axes either; 0 for a legend outside.
  std::vector<long> legend_ink;
  std::vector<int> legends_left_out;           // panels whose legend had no room at all (a problem)
  std::vector<AxisRange> y_axes;               // per panel: its vertical axis
  AxisRange x_axis;                            // the shared horizontal axis
  std::vector<std::string> series;             // Series::source (or label) of every series drawn
  std::vector<EventLabelReport> event_labels;  // every labelled event inside the time window
  double dpi = 0.0;  // a print figure's pixels per inch (Figure::print); 0: a pixel design
};

// Everything wrong with a layout, one line each: two text boxes that overlap, a text or a
// legend that leaves the image, a legend over another legend, an event label over a legend
// (legend entries may of course sit inside their own legend), an event's leader across a
// text, a legend left out for want of room. Empty: a clean layout.
std::vector<std::string> layout_problems(const FigureLayout& layout);

}  // namespace stiction::plot
