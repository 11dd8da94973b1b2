#include "plot/figure.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "plot/cairo_font.hpp"
#include "plot/event_marks.hpp"
#include "plot/figure_drawing.hpp"
#include "plot/legend.hpp"
#include "plot/painter.hpp"
#include "plot/series_strokes.hpp"
#include "plot/style.hpp"
#include "plot/text_fit.hpp"
#include "plot/ticks.hpp"
#include "plot/y_axis.hpp"

namespace stiction::plot {

std::optional<Format> parse_format(const std::string& name) {
  std::string lower;
  for (char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "png") return Format::png;
  if (lower == "svg") return Format::svg;
  if (lower == "pdf") return Format::pdf;
  return std::nullopt;
}

const char* extension(Format format) {
  switch (format) {
    case Format::svg:
      return ".svg";
    case Format::pdf:
      return ".pdf";
    case Format::png:
      break;
  }
  return ".png";
}

PixelSize pixel_size(const Figure& figure) {
  if (!figure.print) return {figure.width, figure.height};
  auto pixels = [&](double mm) {
    const double p = std::round(mm / 25.4 * figure.print->dpi);
    return std::isfinite(p) ? static_cast<int>(std::clamp(p, 0.0, 1e6)) : 0;
  };
  return {pixels(figure.print->width_mm), pixels(figure.print->height_mm)};
}

namespace {

void check_size(const Figure& figure) {
  const PixelSize size = pixel_size(figure);
  if (size.width < 200 || size.height < 150 || size.width > 16384 || size.height > 16384) {
    throw std::invalid_argument("figure size must be between 200x150 and 16384x16384 pixels" +
                                std::string(figure.print ? " (the print size at its dpi)" : ""));
  }
  if (figure.print && !(figure.print->font_pt > 0.0 && figure.print->font_pt < 100.0)) {
    throw std::invalid_argument("figure font size must be between 0 and 100 pt");
  }
}

}  // namespace

namespace {

// Reference lines under the data, across the frame.
void draw_references(Painter& painter, const Panel& panel, const Axis& y, const Rect& f,
                     const Metrics& m) {
  const Stroke stroke = make_stroke(reference_style(), m.line);
  for (const ReferenceLine& r : panel.references) {
    const double py = y.map(r.y);
    if (!std::isfinite(py) || py < f.y0 || py > f.y1) continue;
    painter.line({f.x0, py}, {f.x1, py}, stroke);
  }
}

}  // namespace

FigureLayout draw(const Figure& figure, cairo_t* cr) { return draw_figure(figure, cr, nullptr); }

FigureLayout draw_figure(const Figure& given, cairo_t* cr, std::vector<PlacedText>* texts) {
  check_size(given);
  // A legend entry shown in an earlier panel's legend is not repeated (legend.hpp).
  const Figure figure = shared_legend_entries(given);
  const PixelSize size = pixel_size(figure);
  FigureLayout layout;
  layout.width = size.width;
  layout.height = size.height;
  if (figure.print) layout.dpi = figure.print->dpi;
  const CairoFont font = CairoFont::open_default();
  Painter painter(cr, font, layout, texts);
  painter.fill_rect(Rect{0, 0, static_cast<double>(size.width), static_cast<double>(size.height)},
                    kWhite);
  const Metrics m = figure_metrics(figure, size.width, size.height);
  const double s = m.s;

  // ---- The shared horizontal axis range.
  std::vector<double> xs;
  for (const Panel& p : figure.panels) {
    for (const Series& series : p.series) xs.insert(xs.end(), series.x.begin(), series.x.end());
  }
  Range xr = finite_range(xs);
  if (figure.x_min) xr.min = *figure.x_min;
  if (figure.x_max) xr.max = *figure.x_max;
  double x_lo = xr.min, x_hi = xr.max;
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi) || !(x_hi > x_lo)) {
    const Ticks t = nice_ticks(x_lo, x_hi, 2);
    x_lo = t.lo;
    x_hi = t.hi;
  }

  // ---- Vertical layout.
  const Extent tick_extent = painter.measure("0123456789", m.tick());
  const Extent label_extent = painter.measure("Hg[]", m.label());
  const Extent event_extent = painter.measure("Hg", m.event());
  const double label_line = label_extent.line_ascent + label_extent.line_descent;
  const double margin_width = size.width - 2 * m.margin();
  // The title by the text rule: on one line in the pixel design, on up to two in print.
  double title_size = m.title();
  std::vector<std::string> title_lines;
  bool title_shortened = false;
  if (!figure.title.empty()) {
    const FittedText title = fit_text(
        painter, figure.title,
        TextRule{m.title(), m.floor(m.title()), margin_width, std::size_t{m.shrinks ? 1u : 2u}});
    title_lines = title.lines;
    title_size = title.size;
    title_shortened = title.shortened;
  }
  const Extent title_extent = painter.measure("Hg", title_size);
  const double title_line = title_extent.line_ascent + title_extent.line_descent;
  double top = m.margin();
  const double title_baseline = top + title_extent.line_ascent;
  if (!title_lines.empty()) {
    top =
        title_baseline + (title_lines.size() - 1) * title_line + title_extent.line_descent + 14 * s;
  }
  // Many labelled events: full-height lines would hide the data; they become marks along the
  // top and bottom edge of each panel.
  const bool event_rug =
      std::count_if(figure.events.begin(), figure.events.end(),
                    [](const EventMarker& e) { return e.labelled; }) > kMaxEventLines;
  int event_rows = std::any_of(figure.events.begin(), figure.events.end(),
                               [](const EventMarker& e) { return e.labelled; })
                       ? 1
                       : 0;
  // The key of the event marks' styles, when some event is drawn without a label: beside the
  // time axis title, or on a line of its own under it when there is no room beside it.
  const EventKey key = event_key(painter, figure.events, m);
  bool key_below = false;
  const double event_line = event_extent.line_ascent + event_extent.line_descent;

  const double bottom_base = m.margin() + label_line + 8 * s + tick_extent.line_ascent +
                             tick_extent.line_descent + m.tick_length() + 4 * s;
  const std::size_t n_panels = std::max<std::size_t>(1, figure.panels.size());
  // Captions sit above their panel, in a taller gap.
  const bool captions = std::any_of(figure.panels.begin(), figure.panels.end(),
                                    [](const Panel& p) { return !p.caption.empty(); });
  const Extent caption_extent = painter.measure("Hg", m.event());
  const double caption_line =
      captions ? caption_extent.line_ascent + caption_extent.line_descent + 6 * s : 0.0;
  // Log axes (and fixed ranges) put labelled ticks on the frame's edges: the gap then leaves
  // room for a tick label above and one below.
  const bool edge_ticks = std::any_of(figure.panels.begin(), figure.panels.end(),
                                      [](const Panel& p) { return p.log || (p.y_min && p.y_max); });
  const double tick_line = tick_extent.line_ascent + tick_extent.line_descent;
  // Between panels: room for the tick labels at the frames' edges; with captions, the caption
  // row (left of the frame nothing but tick labels sits, so the two share the height).
  const double tick_gap = edge_ticks ? std::max(26 * s, tick_line + 4 * s) : 26 * s;
  const double gap = captions ? std::max(tick_gap, caption_line + 8 * s) : tick_gap;
  const Panel empty_panel;
  auto panel_at = [&](std::size_t p) -> const Panel& {
    return p < figure.panels.size() ? figure.panels[p] : empty_panel;
  };

  // Passes: the layout depends on itself (left margin <- tick labels <- panel height <- event
  // rows <- horizontal mapping <- margins; legends beside the axes move the right edge).
  double left = 0.0, right = 0.0;
  std::vector<Rect> frames;
  std::vector<YAxis> y_axes;
  std::vector<YTitle> y_titles;
  EventLabelPlan event_plan;
  bool with_key = false;
  std::string x_title;
  double x_title_size = m.label();
  bool x_title_shortened = false;
  std::string x_title_given;
  std::vector<Legend> legends(n_panels);
  std::vector<Rect> legend_boxes(n_panels);  // inside places (chosen each pass)
  // Where each legend goes: it moves only from inside to above to beside the axes, and back
  // inside only for good (`crowded`), so the passes converge.
  std::vector<LegendPlace> places(n_panels, LegendPlace::inside);
  // Legends with no room outside the axes either; the data under each legend inside (reported).
  std::vector<bool> crowded(n_panels, false);
  std::vector<long> legend_ink(n_panels, 0);
  // Room reserved above each panel and beside the axes for legends there; like the event rows
  // it only grows from pass to pass (but for a legend that leaves the place above, which
  // happens at most once), so the passes settle.
  std::vector<double> above(n_panels, 0.0);
  // Rows a legend above may take: two, or all its entries' when it has no other place.
  std::vector<int> above_rows(n_panels, 2);
  auto n_entries = [&](std::size_t p) {
    return static_cast<int>(legend_entries(panel_at(p)).size());
  };
  double outside_width = 0.0;
  Ticks x_ticks;
  TickLabels x_labels;
  // Every vertical axis keeps two labelled ticks: per panel, finer ticks than its height
  // asks for, labelled minor ticks on a log axis, and time axis labels that give way to them.
  std::vector<int> y_finer(n_panels, 0);
  std::vector<bool> y_minor_labels(n_panels, false);
  std::vector<double> hidden_x_values;
  std::vector<std::vector<YLabel>> y_labels(n_panels);
  // The time axis' labels under the bottom frame, but those that gave way.
  auto x_label_boxes = [&](const Axis& x_axis) {
    std::vector<Rect> boxes;
    const double baseline = frames.back().y1 + m.tick_length() + tick_extent.line_ascent;
    for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
      if (std::find(hidden_x_values.begin(), hidden_x_values.end(), x_ticks.values[i]) !=
          hidden_x_values.end()) {
        continue;
      }
      const double px = std::round(x_axis.map(x_ticks.values[i])) + 0.5;
      const double w = painter.measure(x_labels.labels[i], m.tick()).width;
      boxes.push_back(Rect{px - 0.5 * w - 2 * s, baseline - tick_extent.line_ascent,
                           px + 0.5 * w + 2 * s, baseline + tick_extent.line_descent});
    }
    return boxes;
  };
  // A legend in the panel's caption row: one unboxed row right of the caption, when the
  // figure has caption rows; it costs the data no room. The caption stays whole, at its size
  // or smaller down to the floor of its text (the text rule).
  auto caption_row_legend = [&](std::size_t p, const Rect& f) -> std::optional<Legend> {
    if (!captions) return std::nullopt;
    const std::string& caption = panel_at(p).caption;
    const double taken =
        caption.empty() ? 0.0 : painter.measure(caption, m.floor(m.event())).width + 20 * s;
    return legend_in_caption_row(panel_at(p), painter, m, f.width() - taken);
  };
  std::vector<std::vector<std::vector<Point>>> lines(n_panels);
  for (int pass = 0; pass < 8; ++pass) {
    double above_total = 0.0;
    for (double a : above) above_total += a;
    const double panels_top = top + caption_line;
    const double events_height = event_rows_height(painter, event_rows, m);
    const double bottom_reserved = bottom_base + (key_below ? event_line + 6 * s : 0.0);
    const double panels_bottom = size.height - bottom_reserved;
    const double panel_h = std::max(
        10.0, (panels_bottom - panels_top - events_height - above_total - gap * (n_panels - 1)) /
                  static_cast<double>(n_panels));
    const int y_target = std::clamp(static_cast<int>(panel_h / (58 * s)), 2, 8);
    y_axes.clear();
    y_titles.clear();
    double tick_width = 0.0;
    std::size_t max_lines = 1;
    for (std::size_t p = 0; p < n_panels; ++p) {
      YAxis y = make_y_axis(panel_at(p), x_lo, x_hi, y_target + y_finer[p]);
      if (y_minor_labels[p]) label_minor_ticks(y);
      for (const TickMark& t : y.ticks) {
        if (!t.label.empty())
          tick_width = std::max(tick_width, painter.measure(t.label, m.tick()).width);
      }
      y_titles.push_back(fit_y_title(painter,
                                     axis_title(panel_at(p).label, panel_at(p).unit, y.exponent),
                                     panel_h, m.label(), m.floor(m.label()), m.y_title_lines));
      max_lines = std::max(max_lines, y_titles.back().lines.size());
      y_axes.push_back(std::move(y));
    }
    left = m.margin() + max_lines * label_line + 10 * s + tick_width + m.tick_length() + 2 * s;

    // Horizontal ticks: as many as fit without their labels touching.
    for (int x_target = std::max(3, static_cast<int>(size.width / (m.x_tick_spacing * s)));;
         --x_target) {
      const Ticks loose = nice_ticks(x_lo, x_hi, x_target);
      x_ticks = loose;
      x_ticks.values.clear();
      for (double v : loose.values) {
        if (in_range(v, x_lo, x_hi)) x_ticks.values.push_back(v);
      }
      if (x_ticks.values.empty()) x_ticks.values = {x_lo, x_hi};
      x_ticks.lo = x_ticks.values.front();
      x_ticks.hi = x_ticks.values.back();
      x_labels = format_ticks(x_ticks);
      right = size.width - outside_width -
              std::max(m.margin() + 10 * s,
                       0.5 * painter.measure(x_labels.labels.back(), m.tick()).width + m.margin());
      const Axis probe{x_lo, x_hi, false, left, right};
      bool crowded = false;
      for (std::size_t i = 1; i < x_ticks.values.size(); ++i) {
        const double room = probe.map(x_ticks.values[i]) - probe.map(x_ticks.values[i - 1]);
        const double need = 0.5 * (painter.measure(x_labels.labels[i], m.tick()).width +
                                   painter.measure(x_labels.labels[i - 1], m.tick()).width) +
                            0.8 * m.tick();
        if (room < need) crowded = true;
      }
      if (!crowded || x_target <= 2) break;
    }

    frames.clear();
    double y0 = panels_top + events_height;
    for (std::size_t p = 0; p < n_panels; ++p) {
      y0 += above[p];
      frames.push_back(
          Rect{std::round(left), std::round(y0), std::round(right), std::round(y0 + panel_h)});
      y0 += panel_h + gap;
    }
    const Axis x_axis{x_lo, x_hi, false, frames[0].x0, frames[0].x1};
    // The panels' width with no legend beside them.
    const double free_width = frames[0].width() + outside_width;

    // Legends: inside where they cover the least data, when that is little (legend.hpp); else
    // above the panel or beside the axes on the right, whichever costs the data less room.
    bool moved = false;
    for (std::size_t p = 0; p < n_panels; ++p) {
      const Rect& f = frames[p];
      YAxis& y = y_axes[p];
      y.axis.p0 = f.y1;
      y.axis.p1 = f.y0;
      lines[p].clear();
      for (const Series& series : panel_at(p).series)
        lines[p].push_back(to_pixels(series, x_axis, y.axis));
      if (legend_entries(panel_at(p)).empty()) continue;
      if (places[p] == LegendPlace::inside) {
        // What the panel shows, as drawn: its data (reference lines and series) and its
        // event marks, apart (a legend may cover a mark more readily than data).
        const DataInk data(f, font, [&](Painter& mask) {
          draw_references(mask, panel_at(p), y.axis, f, m);
          draw_series(mask, panel_at(p), lines[p], f, m.line, nullptr);
        });
        const DataInk marks(f, font, [&](Painter& mask) {
          draw_event_marks(mask, figure.events, x_axis, f, event_rug, m);
        });
        const PanelInk ink{data, marks};
        // Inside at the legend's size; else in the caption row (no room taken, nothing
        // covered); else inside at the floor of its text (a smaller legend inside costs the
        // data less than one above or beside the axes).
        if (const auto inside =
                free_place_inside(panel_at(p), painter, m, f, ink, m.legend(), legend_ink[p])) {
          legends[p] = inside->legend;
          legend_boxes[p] = inside->box;
          continue;
        }
        if (!crowded[p]) {
          if (auto row = caption_row_legend(p, f)) {
            places[p] = LegendPlace::caption;
            legends[p] = std::move(*row);
            moved = true;
            continue;
          }
        }
        if (const auto inside = free_place_inside(panel_at(p), painter, m, f, ink,
                                                  m.floor(m.legend()), legend_ink[p])) {
          legends[p] = inside->legend;
          legend_boxes[p] = inside->box;
          continue;
        }
        if (crowded[p]) {
          // No free corner and no room above in two rows or beside the axes: above the
          // panel all the same, in as many rows as it takes, its labels shortened by the text
          // rule if they must be -- never over the data (a legend there hid Fig. 7's torque
          // band). Left out, and reported, when the panels would keep no room for two tick
          // labels.
          const Legend tall = legend_above_anyhow(panel_at(p), painter, m, f.width());
          if (tall.width > f.width() + 0.5 ||
              panel_h - (tall.height + 6 * s) / static_cast<double>(n_panels) <= 2 * tick_line) {
            legends[p] = Legend{};
            legend_ink[p] = 0;
            continue;
          }
          places[p] = LegendPlace::above;
          above_rows[p] = n_entries(p);
          moved = true;
        } else {
          // Outside: in the caption row when it fits there (no room taken), else where it costs
          // the data least room, as a fraction of the figure (beside
          // the axes every panel narrows, unless a legend is there already), a legend with
          // shortened labels counting as worse beside and not going above at all.
          const Legend on_top = legend_above(panel_at(p), painter, m, f.width(), 2);
          // Beside the axes at most 40% of the figure's width and half the panels' width, or
          // the width of the legends there already (its labels smaller, down to their floor, or
          // shortened to fit).
          const double beside_width =
              std::min(0.4 * size.width, std::max(0.5 * free_width, outside_width) - 16 * s);
          const Legend beside =
              legend_beside(panel_at(p), painter, m, beside_width, frames.back().y1 - f.y0);
          // Not above when that would leave the panels too short to hold two tick labels, nor
          // in more than two rows (a column of entries goes beside the axes).
          const bool room_above =
              on_top.rows <= 2 && !on_top.shortened && on_top.width <= f.width() &&
              panel_h - (on_top.height + 6 * s) / static_cast<double>(n_panels) > 3 * tick_line;
          const double cost_above = room_above ? (on_top.height + 6 * s) / size.height
                                               : std::numeric_limits<double>::infinity();
          // Not beside when the panels would keep less than half the width they have without
          // legends beside them (a legend as narrow as those there already costs nothing).
          const double narrower = std::max(0.0, beside.width + 16 * s - outside_width);
          const bool room_beside = beside.width + 16 * s <= outside_width + 0.5 ||
                                   beside.width + 16 * s <= 0.5 * free_width;
          const double cost_beside = room_beside
                                         ? narrower / size.width + (beside.shortened ? 0.15 : 0.0)
                                         : std::numeric_limits<double>::infinity();
          moved = true;
          if (std::isinf(cost_above) && std::isinf(cost_beside)) {
            // Above in as many rows as it takes, labels whole, while the panels keep room for
            // two tick labels; else inside where the least data is (the next pass).
            const Legend tall = legend_above(panel_at(p), painter, m, f.width(), n_entries(p));
            if (tall.shortened || tall.width > f.width() ||
                panel_h - (tall.height + 6 * s) / static_cast<double>(n_panels) <= 3 * tick_line) {
              crowded[p] = true;
              continue;
            }
            places[p] = LegendPlace::above;
            above_rows[p] = n_entries(p);
          } else {
            places[p] = cost_above <= cost_beside ? LegendPlace::above : LegendPlace::right;
          }
        }
      }
      if (places[p] == LegendPlace::caption) {
        if (auto row = caption_row_legend(p, f)) {
          legends[p] = std::move(*row);
          continue;
        }
        // No longer fits beside the caption as the panels narrowed: above the panel (a place
        // changes only in the order inside, caption row, above, beside, so the passes settle).
        places[p] = LegendPlace::above;
        moved = true;
      }
      if (places[p] == LegendPlace::above && crowded[p]) {
        // Above because it has no other place: whatever shape fits the panel's width.
        legends[p] = legend_above_anyhow(panel_at(p), painter, m, f.width());
        if (legends[p].height + 6 * s > above[p] + 0.5) {
          above[p] = legends[p].height + 6 * s;
          moved = true;
        }
      } else if (places[p] == LegendPlace::above) {
        legends[p] = legend_above(panel_at(p), painter, m, f.width(), above_rows[p]);
        if (legends[p].rows > above_rows[p] || legends[p].shortened ||
            legends[p].width > f.width() + 0.5) {
          // No longer whole as the panels narrowed: beside the axes instead (a
          // place changes at most from inside to above to beside to inside, so the passes
          // still settle), its room above given back.
          places[p] = LegendPlace::right;
          above[p] = 0.0;
          moved = true;
        } else if (legends[p].height + 6 * s > above[p] + 0.5) {
          above[p] = legends[p].height + 6 * s;
          moved = true;
        }
      }
      if (places[p] == LegendPlace::right) {
        // Beside the axes the legend may hang down to the next panel with a legend there.
        double column_bottom = frames.back().y1;
        for (std::size_t q = p + 1; q < n_panels; ++q) {
          if (places[q] == LegendPlace::right) {
            column_bottom = frames[q].y0 - 10 * s;
            break;
          }
        }
        legends[p] = legend_beside(
            panel_at(p), painter, m,
            std::min(0.4 * size.width, std::max(0.5 * free_width, outside_width) - 16 * s),
            std::max(f.height(), column_bottom - f.y0));
        if (legends[p].width + 16 * s > std::max(0.5 * free_width, outside_width + 0.5)) {
          // Grown too wide as the panels changed (more columns): inside, where the least
          // data is, rather than squeezing the panels.
          places[p] = LegendPlace::inside;
          crowded[p] = true;
          moved = true;
        } else if (legends[p].width + 16 * s > outside_width + 0.5) {
          outside_width = legends[p].width + 16 * s;
          moved = true;
        }
      }
    }

    // Tick labels, and at least two on every vertical axis.
    {
      std::vector<Rect> taken = x_label_boxes(x_axis);
      for (std::size_t p = 0; p < n_panels; ++p) {
        const Rect& f = frames[p];
        auto select = [&](const YAxis& y, std::vector<Rect>& boxes) {
          return select_y_labels(painter, y, f, m, boxes);
        };
        std::vector<Rect> trial = taken;
        y_labels[p] = select(y_axes[p], trial);
        // Finer ticks keep a label away from the neighbour it touched.
        for (int finer = 1; finer <= 6 && y_labels[p].size() < 2; ++finer) {
          YAxis alt = make_y_axis(panel_at(p), x_lo, x_hi, y_target + y_finer[p] + finer);
          if (y_minor_labels[p]) label_minor_ticks(alt);
          alt.axis.p0 = f.y1;
          alt.axis.p1 = f.y0;
          std::vector<Rect> alt_taken = taken;
          std::vector<YLabel> alt_labels = select(alt, alt_taken);
          if (alt_labels.size() >= 2) {
            y_finer[p] += finer;
            y_axes[p] = std::move(alt);
            y_labels[p] = std::move(alt_labels);
            trial = std::move(alt_taken);
            moved = true;
          }
        }
        // A log axis within about a decade: its minor ticks at 2 and 5 get labels.
        if (y_labels[p].size() < 2 && y_axes[p].axis.log && !y_minor_labels[p]) {
          y_minor_labels[p] = true;
          label_minor_ticks(y_axes[p]);
          trial = taken;
          y_labels[p] = select(y_axes[p], trial);
          moved = true;
        }
        // Still one: the time axis' labels under it give way (the time axis has more).
        if (y_labels[p].size() < 2 && p + 1 == n_panels) {
          std::vector<Rect> alone;  // this axis' labels with nothing in their way
          const std::vector<YLabel> wanted = select(y_axes[p], alone);
          for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
            const double px = std::round(x_axis.map(x_ticks.values[i])) + 0.5;
            const double w = painter.measure(x_labels.labels[i], m.tick()).width;
            const double baseline = f.y1 + m.tick_length() + tick_extent.line_ascent;
            const Rect box{px - 0.5 * w - 2 * s, baseline - tick_extent.line_ascent,
                           px + 0.5 * w + 2 * s, baseline + tick_extent.line_descent};
            if (std::any_of(wanted.begin(), wanted.end(),
                            [&](const YLabel& l) { return l.box.overlaps(box); })) {
              hidden_x_values.push_back(x_ticks.values[i]);
              moved = true;
            }
          }
          taken = x_label_boxes(x_axis);
          for (std::size_t q = 0; q < p; ++q) {
            for (const YLabel& l : y_labels[q]) taken.push_back(l.box);
          }
          trial = taken;
          y_labels[p] = select(y_axes[p], trial);
        }
        taken = std::move(trial);
      }
    }

    // Event labels at their marks; the key when some event is drawn without one.
    // Not left of the top panel: its highest tick label reaches above the frame.
    event_plan = place_event_labels(painter, figure.events, x_axis, frames[0], frames[0].x0,
                                    size.width - m.margin(), m);
    with_key =
        !event_plan.all_placed ||
        std::any_of(figure.events.begin(), figure.events.end(), [&](const EventMarker& e) {
          const double px = x_axis.map(e.x);
          return !e.labelled && std::isfinite(px) && px >= frames[0].x0 && px <= frames[0].x1;
        });
    x_title_given = axis_title(figure.x_label, figure.x_unit, x_labels.exponent);
    const FittedText x_fitted = fit_text(
        painter, x_title_given, TextRule{m.label(), m.floor(m.label()), frames.back().width(), 1});
    x_title = x_fitted.joined();
    x_title_size = x_fitted.size;
    x_title_shortened = x_fitted.shortened;
    const double x_title_half = 0.5 * painter.measure(x_title, x_title_size).width;
    const double centre = 0.5 * (frames.back().x0 + frames.back().x1);
    const bool key_beside = size.width - m.margin() - key.width >= centre + x_title_half + 16 * s ||
                            m.margin() + key.width <= centre - x_title_half - 16 * s;
    const bool needs_below = with_key && !key_beside;
    const int needed = std::max(event_plan.rows, event_rows);
    if (needed == event_rows && !moved && (!needs_below || key_below)) break;
    event_rows = needed;
    key_below = key_below || needs_below;
  }

  const Axis x_axis{x_lo, x_hi, false, frames[0].x0, frames[0].x1};
  layout.x_axis = AxisRange{x_lo, x_hi, false};

  // ---- Title.
  const TextOrigin title_origin{figure.title, title_shortened};
  for (std::size_t k = 0; k < title_lines.size(); ++k) {
    const double w = painter.measure(title_lines[k], title_size).width;
    const double cx = 0.5 * (frames[0].x0 + frames[0].x1);
    painter.text(title_lines[k], std::clamp(cx - 0.5 * w, m.margin(), size.width - w - m.margin()),
                 title_baseline + k * title_line, title_size, kText, TextRole::title, -1, false,
                 &title_origin);
  }

  const Stroke frame_stroke{kFrame, m.frame_width(), {}};
  const Stroke grid_stroke{kGrid, m.grid_width(), {}};
  const Stroke minor_stroke{kMinorGrid, m.grid_width(), {}};
  const double tick_baseline = frames.back().y1 + m.tick_length() + tick_extent.line_ascent;

  for (std::size_t p = 0; p < n_panels; ++p) {
    const Panel& panel = panel_at(p);
    const Rect& f = frames[p];
    const YAxis& y = y_axes[p];
    const int pi = static_cast<int>(p);
    layout.panels.push_back(f);
    layout.y_axes.push_back(
        y.axis.log ? AxisRange{std::pow(10.0, y.axis.lo), std::pow(10.0, y.axis.hi), true}
                   : AxisRange{y.axis.lo, y.axis.hi, false});

    // Grid.
    for (const TickMark& t : y.ticks) {
      const double py = std::round(y.axis.map(t.value)) + 0.5;
      painter.line({f.x0, py}, {f.x1, py}, t.label.empty() ? minor_stroke : grid_stroke);
    }
    for (double v : x_ticks.values) {
      const double px = std::round(x_axis.map(v)) + 0.5;
      painter.line({px, f.y0}, {px, f.y1}, grid_stroke);
    }
    draw_event_marks(painter, figure.events, x_axis, f, event_rug, m);
    draw_references(painter, panel, y.axis, f, m);
    draw_series(painter, panel, lines[p], f, m.line, &layout);
    // Frame and ticks.
    const Rect crisp{f.x0 + 0.5, f.y0 + 0.5, f.x1 - 0.5, f.y1 - 0.5};
    painter.stroke_rect(crisp, frame_stroke);
    draw_y_ticks(painter, y, f, m, frame_stroke, y_labels[p], pi);
    for (double v : x_ticks.values) {
      const double px = std::round(x_axis.map(v)) + 0.5;
      painter.line({px, f.y1 - m.tick_length()}, {px, f.y1}, frame_stroke);
      painter.line({px, f.y0}, {px, f.y0 + m.tick_length()}, frame_stroke);
    }
    draw_y_title(painter, y_titles[p], f, m, pi);
    // Caption, left-aligned above the frame (above the event labels on the top panel and a
    // legend above the panel).
    if (!panel.caption.empty()) {
      const double above = (p == 0 ? event_rows_height(painter, event_rows, m) : 0.0) +
                           (legends[p].place == LegendPlace::above && !legends[p].entries.empty()
                                ? legends[p].height + 6 * s
                                : 0.0);
      // Beside a legend in the caption row it keeps the room left of it.
      const double legend_room =
          legends[p].place == LegendPlace::caption && !legends[p].entries.empty()
              ? legends[p].width + 20 * s
              : 0.0;
      const FittedText caption =
          fit_text(painter, panel.caption,
                   TextRule{m.event(), m.floor(m.event()), f.width() - legend_room, 1});
      const TextOrigin caption_origin{panel.caption, caption.shortened};
      painter.text(caption.joined(), f.x0, f.y0 - above - 5 * s - caption_extent.line_descent,
                   caption.size, kText, TextRole::note, pi, false, &caption_origin);
    }
    // Legend: inside at its free place, above the panel (right-aligned, over the event
    // labels of the top panel) or beside the axes.
    const Legend& L = legends[p];
    if (L.entries.empty()) {
      if (!legend_entries(panel).empty()) layout.legends_left_out.push_back(pi);
      continue;
    }
    Rect box = legend_boxes[p];
    if (L.place == LegendPlace::right) {
      box = Rect{f.x1 + 16 * s, f.y0, f.x1 + 16 * s + L.width, f.y0 + L.height};
    } else if (L.place == LegendPlace::caption) {
      const double bottom_edge =
          f.y0 - (p == 0 ? event_rows_height(painter, event_rows, m) : 0.0) - 5 * s;
      box = Rect{f.x1 - L.width, bottom_edge - L.height, f.x1, bottom_edge};
    } else if (L.place == LegendPlace::above) {
      const double bottom_edge =
          f.y0 - (p == 0 ? event_rows_height(painter, event_rows, m) : 0.0) - 6 * s;
      box = Rect{f.x1 - L.width, bottom_edge - L.height, f.x1, bottom_edge};
    }
    box = Rect{std::round(box.x0), std::round(box.y0), std::round(box.x1), std::round(box.y1)};
    layout.legends.push_back(box);
    layout.legend_outside.push_back(L.place != LegendPlace::inside);
    layout.legend_panels.push_back(pi);
    layout.legend_ink.push_back(L.place == LegendPlace::inside ? legend_ink[p] : 0);
    draw_legend(painter, panel, L, box, pi, m);
  }

  // ---- Horizontal tick labels and axis title under the bottom panel.
  const Rect& bottom = frames.back();
  for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
    if (std::find(hidden_x_values.begin(), hidden_x_values.end(), x_ticks.values[i]) !=
        hidden_x_values.end()) {
      continue;  // gave way to a vertical axis' label
    }
    const double px = std::round(x_axis.map(x_ticks.values[i])) + 0.5;
    const double w = painter.measure(x_labels.labels[i], m.tick()).width;
    painter.text(x_labels.labels[i], px - 0.5 * w, tick_baseline, m.tick(), kText,
                 TextRole::tick_label, static_cast<int>(n_panels) - 1);
  }
  const double xw = painter.measure(x_title, x_title_size).width;
  const double x_title_baseline =
      tick_baseline + tick_extent.line_descent + 8 * s + label_extent.line_ascent;
  const TextOrigin x_title_origin{x_title_given, x_title_shortened};
  const Rect x_title_box =
      painter.text(x_title, 0.5 * (bottom.x0 + bottom.x1) - 0.5 * xw, x_title_baseline,
                   x_title_size, kText, TextRole::axis_label, -1, false, &x_title_origin);

  // ---- Event labels above the top panel, at their marks; the key beside the time axis title.
  draw_event_labels(painter, event_plan, figure.events, frames[0], m, layout);
  if (with_key) {
    double key_x = size.width - m.margin() - key.width;
    double key_baseline = x_title_baseline;
    if (key_x < x_title_box.x1 + 16 * s) key_x = m.margin();
    if (key_x + key.width > x_title_box.x0 - 16 * s && key_x == m.margin()) {
      key_x = size.width - m.margin() - key.width;
      key_baseline = x_title_box.y1 + 6 * s + event_extent.line_ascent;
    }
    draw_event_key(painter, key, key_x, key_baseline, m);
  }
  return layout;
}

}  // namespace stiction::plot
