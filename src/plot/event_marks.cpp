#include "plot/event_marks.hpp"

#include <algorithm>
#include <cmath>

#include "plot/text_fit.hpp"

namespace stiction::plot {
namespace {

using Label = EventLabelPlan::Label;

enum class Mode { centred, right, left };

// Marks closer than this (pixels) are one mark: their labels may stack in a column over it.
constexpr double kSameMark = 3.0;

bool covers(const Label& l, double x, double margin) {
  return l.row >= 0 && x >= l.x0 - margin && x <= l.x1 + margin;
}

// The horizontal extent a label takes in its row: its box, and the leader to its mark.
std::pair<double, double> occupied(const Label& l) {
  return {std::min(l.x0, l.mark_x), std::max(l.x1, l.mark_x)};
}

// A label with a line up from its mark through the rows below it (not stacked on a label of
// the same mark, not in row 0 over its mark).
bool has_vertical_leader(const Label& l, const std::vector<Label>& placed) {
  if (l.row < 0) return false;
  if (l.beside) return true;
  if (l.row == 0) return false;
  return std::none_of(placed.begin(), placed.end(), [&](const Label& below) {
    return below.row == l.row - 1 && !below.beside &&
           std::abs(below.mark_x - l.mark_x) <= kSameMark && covers(below, l.mark_x, 0.0);
  });
}

// Whether `l` (row, box, mode set) fits among the labels placed so far.
bool fits(const Label& l, const std::vector<Label>& placed, double left, double right, double gap) {
  const auto [a, b] = occupied(l);
  if (a < left - 0.5 || b > right + 0.5) return false;
  // Stacked directly over a label of the same mark: no leader needed.
  bool stacked = false;
  if (!l.beside && l.row > 0) {
    for (const Label& p : placed) {
      if (p.row == l.row - 1 && covers(p, l.mark_x, 0.0)) {
        if (p.beside || std::abs(p.mark_x - l.mark_x) > kSameMark) return false;
        stacked = true;
      }
    }
  }
  for (const Label& p : placed) {
    if (p.row < 0) continue;
    // Neighbours in the row, a gap apart.
    if (p.row == l.row) {
      const auto [u, v] = occupied(p);
      if (a < v + gap && b > u - gap) return false;
    }
    // A line from this label's mark up to its row crosses no label below it.
    const bool vertical = l.beside || (l.row > 0 && !stacked);
    if (vertical && p.row < l.row && covers(p, l.mark_x, 0.5 * gap)) return false;
    // Nor does this label cover a line from a higher label's mark.
    if (p.row > l.row && has_vertical_leader(p, placed) && p.mark_x >= a - 0.5 * gap &&
        p.mark_x <= b + 0.5 * gap) {
      return false;
    }
  }
  return true;
}

double row_height(const Extent& e, const Metrics& m) {
  return e.line_ascent + e.line_descent + 4 * m.s;
}

Rect label_box(const Label& l, const Rect& top_frame, const Extent& e, const Metrics& m) {
  const double y1 = top_frame.y0 - 6 * m.s - l.row * row_height(e, m);
  return Rect{l.x0, y1 - e.line_ascent - e.line_descent, l.x1, y1};
}

}  // namespace

namespace {

// One greedy pass: labels taken in `order`, each put in the lowest row where one of `modes`
// fits, the whole text first, then shortened.
struct Attempt {
  std::vector<Label> placed;
  int labelled = 0, shortened = 0, rows = 0, leaders = 0;
  double displacement = 0.0;
  // Better: more labels, then fewer shortened, then fewer rows, then fewer leaders, then
  // labels nearer their marks.
  bool better_than(const Attempt& o) const {
    if (labelled != o.labelled) return labelled > o.labelled;
    if (shortened != o.shortened) return shortened < o.shortened;
    if (rows != o.rows) return rows < o.rows;
    if (leaders != o.leaders) return leaders < o.leaders;
    return displacement < o.displacement - 1e-9;
  }
};

Attempt place_greedily(Painter& painter, const std::vector<Label>& order,
                       const std::vector<std::vector<std::string>>& versions,
                       const std::vector<Mode>& modes, double left, double right,
                       const Metrics& m) {
  const double gap = 12 * m.s, beside = 10 * m.s;
  Attempt attempt;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Label& l = order[i];
    bool done = false;
    for (const std::string& text : versions[i]) {
      const double w = painter.measure(text, m.event()).width;
      const bool shortened = &text != &versions[i].front();
      for (int row = 0; row < kMaxEventRows && !done; ++row) {
        for (Mode mode : modes) {
          Label c = l;
          c.text = text;
          c.shortened = shortened;
          c.row = row;
          c.beside = mode != Mode::centred;
          if (mode == Mode::centred) {
            c.x0 = std::clamp(l.mark_x - 0.5 * w, left, right - w);
            // Pushed off its mark by the figure's edge: a label beside the mark instead.
            if (l.mark_x < c.x0 + 2 || l.mark_x > c.x0 + w - 2) continue;
          } else if (mode == Mode::right) {
            c.x0 = l.mark_x + beside;
          } else {
            c.x0 = l.mark_x - beside - w;
          }
          c.x1 = c.x0 + w;
          if (fits(c, attempt.placed, left, right, gap)) {
            attempt.placed.push_back(c);
            done = true;
            break;
          }
        }
      }
      if (done) break;
    }
    if (!done) {
      Label unplaced = l;
      unplaced.text = versions[i].front();
      unplaced.row = -1;
      attempt.placed.push_back(unplaced);
    }
  }
  for (const Label& l : attempt.placed) {
    if (l.row < 0) continue;
    ++attempt.labelled;
    attempt.shortened += l.shortened ? 1 : 0;
    attempt.rows = std::max(attempt.rows, l.row + 1);
    attempt.leaders += has_vertical_leader(l, attempt.placed) ? 1 : 0;
    attempt.displacement += std::abs(0.5 * (l.x0 + l.x1) - l.mark_x);
  }
  return attempt;
}

double score(const Attempt& a) {
  return a.labelled * 1e6 - a.shortened * 1e5 - a.rows * 1e4 - a.leaders * 1e2 -
         a.displacement * 1e-3;
}

Attempt scored(std::vector<Label> placed) {
  Attempt a;
  a.placed = std::move(placed);
  for (const Label& l : a.placed) {
    if (l.row < 0) continue;
    ++a.labelled;
    a.shortened += l.shortened ? 1 : 0;
    a.rows = std::max(a.rows, l.row + 1);
    a.leaders += has_vertical_leader(l, a.placed) ? 1 : 0;
    a.displacement += std::abs(0.5 * (l.x0 + l.x1) - l.mark_x);
  }
  return a;
}

// Depth-first over the labels in time order: each label takes one of its candidate places
// (text version x row x mode) that fits, or none; branches that cannot beat the best so far
// are cut, and the search stops after a fixed number of placement trials.
void search_improvement(Painter& painter, const std::vector<Label>& wanted,
                        const std::vector<std::vector<std::string>>& versions, double left,
                        double right, const Metrics& m, Attempt& best) {
  const double gap = 12 * m.s, beside = 10 * m.s;
  std::vector<std::vector<double>> widths;
  for (const auto& v : versions) {
    widths.emplace_back();
    for (const std::string& t : v) widths.back().push_back(painter.measure(t, m.event()).width);
  }
  long budget = 40000;
  double best_score = score(best);
  std::vector<Label> placed;
  int labelled = 0, shortened = 0, rows = 0;
  auto dfs = [&](auto&& self, std::size_t i) -> void {
    if (budget <= 0) return;
    const double bound =
        (labelled + static_cast<double>(wanted.size() - i)) * 1e6 - shortened * 1e5 - rows * 1e4;
    if (bound <= best_score) return;
    if (i == wanted.size()) {
      Attempt a = scored(placed);
      const double sc = score(a);
      if (sc > best_score) {
        best_score = sc;
        best = std::move(a);
      }
      return;
    }
    const Label& l = wanted[i];
    for (std::size_t v = 0; v < versions[i].size(); ++v) {
      const double w = widths[i][v];
      for (int row = 0; row < kMaxEventRows; ++row) {
        for (Mode mode : {Mode::centred, Mode::right, Mode::left}) {
          if (--budget <= 0) return;
          Label c = l;
          c.text = versions[i][v];
          c.shortened = v > 0;
          c.row = row;
          c.beside = mode != Mode::centred;
          if (mode == Mode::centred) {
            c.x0 = std::clamp(l.mark_x - 0.5 * w, left, right - w);
            if (l.mark_x < c.x0 + 2 || l.mark_x > c.x0 + w - 2) continue;
          } else if (mode == Mode::right) {
            c.x0 = l.mark_x + beside;
          } else {
            c.x0 = l.mark_x - beside - w;
          }
          c.x1 = c.x0 + w;
          if (!fits(c, placed, left, right, gap)) continue;
          const int saved_rows = rows;
          placed.push_back(c);
          ++labelled;
          shortened += c.shortened ? 1 : 0;
          rows = std::max(rows, row + 1);
          self(self, i + 1);
          placed.pop_back();
          --labelled;
          shortened -= c.shortened ? 1 : 0;
          rows = saved_rows;
        }
      }
    }
    Label skipped = l;
    skipped.text = versions[i].front();
    skipped.row = -1;
    placed.push_back(skipped);
    self(self, i + 1);
    placed.pop_back();
  };
  dfs(dfs, 0);
}

}  // namespace

EventLabelPlan place_event_labels(Painter& painter, const std::vector<EventMarker>& events,
                                  const Axis& x_axis, const Rect& top_frame, double left,
                                  double right, const Metrics& m) {
  std::vector<Label> wanted;
  for (std::size_t e = 0; e < events.size(); ++e) {
    if (!events[e].labelled) continue;
    const double x = x_axis.map(events[e].x);
    if (!std::isfinite(x) || x < top_frame.x0 - 1 || x > top_frame.x1 + 1) continue;
    Label l;
    l.event = e;
    l.mark_x = x;
    wanted.push_back(l);
  }
  std::stable_sort(wanted.begin(), wanted.end(),
                   [](const Label& a, const Label& b) { return a.mark_x < b.mark_x; });
  // Each label whole (at most 80% of the row), then shortened to about half that, both by the
  // text rule at the labels' size (whole words left out, never a word cut). A shortened label
  // keeps its last three words, the kind and the time ("joint1_… stop 4.651 s"): without
  // them it would not say what happened when.
  std::vector<std::vector<std::string>> versions;
  for (const Label& l : wanted) {
    const TextRule row{m.event(), m.event(), 0.8 * (right - left), 1};
    const std::string full = fit_text(painter, events[l.event].label, row).joined();
    std::size_t tail = full.size();
    for (int words = 0; words < 3 && tail != std::string::npos && tail > 0; ++words) {
      tail = full.rfind(' ', tail - 1);
    }
    const std::string ending = tail == std::string::npos ? full : full.substr(tail);
    const double half_width = std::max(0.5 * painter.measure(full, m.event()).width,
                                       painter.measure("\u2026" + ending, m.event()).width);
    const FittedText half = fit_text(painter, full, TextRule{m.event(), m.event(), half_width, 1});
    const std::string shorter = half.joined();
    const bool keeps_ending =
        shorter.size() >= ending.size() &&
        shorter.compare(shorter.size() - ending.size(), ending.size(), ending) == 0;
    versions.push_back(half.below_floor || shorter == full || !keeps_ending ||
                               tail == std::string::npos
                           ? std::vector<std::string>{full}
                           : std::vector<std::string>{full, shorter});
  }
  // Greedy passes left to right and right to left, with different preferences between a
  // label over its mark and beside it: a label beside its mark, away from the marks still to
  // come, leaves them room (labels beside marks then climb as a staircase). The best wins.
  std::vector<std::size_t> forward(wanted.size()), backward;
  for (std::size_t i = 0; i < forward.size(); ++i) forward[i] = i;
  backward.assign(forward.rbegin(), forward.rend());
  const std::vector<std::vector<Mode>> preferences{{Mode::centred, Mode::right, Mode::left},
                                                   {Mode::centred, Mode::left, Mode::right},
                                                   {Mode::right, Mode::centred, Mode::left},
                                                   {Mode::left, Mode::centred, Mode::right}};
  Attempt best;
  bool first = true;
  for (const std::vector<std::size_t>* order : {&forward, &backward}) {
    std::vector<Label> labels;
    std::vector<std::vector<std::string>> texts;
    for (std::size_t i : *order) {
      labels.push_back(wanted[i]);
      texts.push_back(versions[i]);
    }
    for (const std::vector<Mode>& modes : preferences) {
      Attempt a = place_greedily(painter, labels, texts, modes, left, right, m);
      if (first || a.better_than(best)) best = std::move(a);
      first = false;
    }
  }
  // Then a depth-first search over every label's candidates, from the best greedy pass, within
  // a budget: a few labels (the usual case) are placed as well as they can be.
  search_improvement(painter, wanted, versions, left, right, m, best);
  EventLabelPlan plan;
  plan.labels = std::move(best.placed);
  std::stable_sort(plan.labels.begin(), plan.labels.end(),
                   [](const Label& a, const Label& b) { return a.mark_x < b.mark_x; });
  for (const Label& l : plan.labels) {
    plan.rows = std::max(plan.rows, l.row + 1);
    if (l.row < 0) plan.all_placed = false;
  }
  return plan;
}

double event_rows_height(Painter& painter, int rows, const Metrics& m) {
  if (rows <= 0) return 0.0;
  return rows * row_height(painter.measure("Hg", m.event()), m) + 6 * m.s;
}

void draw_event_marks(Painter& painter, const std::vector<EventMarker>& events, const Axis& x_axis,
                      const Rect& f, bool rug, const Metrics& m) {
  // Unlabelled events first, under the labelled ones' lines.
  const double tick = std::min(12 * m.s, 0.15 * f.height());
  for (const EventMarker& e : events) {
    const double px = x_axis.map(e.x);
    if (!std::isfinite(px) || px < f.x0 || px > f.x1 || e.labelled) continue;
    const Stroke mark = event_tick_stroke(e.kind, m.line);
    painter.line({px, f.y0}, {px, f.y0 + tick}, mark);
    painter.line({px, f.y1 - tick}, {px, f.y1}, mark);
  }
  for (const EventMarker& e : events) {
    const double px = x_axis.map(e.x);
    if (!std::isfinite(px) || px < f.x0 || px > f.x1 || !e.labelled) continue;
    if (rug) {
      Stroke mark = event_stroke(e.kind, m.line);
      mark.dash.clear();
      const double len = std::min(24 * m.s, 0.2 * f.height());
      painter.line({px, f.y0}, {px, f.y0 + len}, mark);
      painter.line({px, f.y1 - len}, {px, f.y1}, mark);
    } else {
      painter.line({px, f.y0}, {px, f.y1}, event_stroke(e.kind, m.line));
    }
  }
}

void draw_event_labels(Painter& painter, const EventLabelPlan& plan,
                       const std::vector<EventMarker>& events, const Rect& top_frame,
                       const Metrics& m, FigureLayout& layout) {
  const Extent e = painter.measure("Hg", m.event());
  for (const Label& l : plan.labels) {
    EventLabelReport report;
    report.event = static_cast<int>(l.event);
    report.mark = {l.mark_x, top_frame.y0};
    if (l.row >= 0) {
      const EventMarker& event = events[l.event];
      const Rect box = label_box(l, top_frame, e, m);
      Stroke leader = event_stroke(event.kind, m.line);
      leader.dash.clear();
      leader.width = 1.2 * m.line;
      const double cy = 0.5 * (box.y0 + box.y1);
      if (l.beside) {
        const double edge = l.x0 > l.mark_x ? box.x0 - 3 * m.s : box.x1 + 3 * m.s;
        report.leader = {{l.mark_x, top_frame.y0}, {l.mark_x, cy}, {edge, cy}};
      } else if (has_vertical_leader(l, plan.labels)) {
        report.leader = {{l.mark_x, top_frame.y0}, {l.mark_x, box.y1}};
      }
      if (!report.leader.empty()) painter.polyline(report.leader, leader);
      report.text = static_cast<int>(layout.texts.size());
      const TextOrigin origin{event.label, l.text != event.label};
      painter.text(l.text, box.x0, box.y1 - e.line_descent, m.event(), event_colour(event.kind),
                   TextRole::event_label, -1, false, &origin);
    }
    layout.event_labels.push_back(std::move(report));
  }
}

EventKey event_key(Painter& painter, const std::vector<EventMarker>& events, const Metrics& m) {
  EventKey key;
  for (const EventMarker& e : events) {
    const std::string kind = e.kind.empty() ? "event" : e.kind;
    if (std::find(key.kinds.begin(), key.kinds.end(), kind) == key.kinds.end()) {
      key.kinds.push_back(kind);
    }
  }
  for (std::size_t k = 0; k < key.kinds.size(); ++k) {
    key.width += (k ? 14 * m.s : 0.0) + 8 * m.s + painter.measure(key.kinds[k], m.event()).width;
  }
  return key;
}

void draw_event_key(Painter& painter, const EventKey& key, double x, double baseline,
                    const Metrics& m) {
  const Extent e = painter.measure("Hg", m.event());
  for (const std::string& kind : key.kinds) {
    // A tick as the marks are drawn, then the kind's name in its colour.
    Stroke sample = event_stroke(kind, m.line);
    sample.dash.clear();
    painter.line({x + 2 * m.s, baseline - 0.8 * e.line_ascent}, {x + 2 * m.s, baseline}, sample);
    x += 8 * m.s;
    x = painter.text(kind, x, baseline, m.event(), event_colour(kind), TextRole::note, -1).x1 +
        14 * m.s;
  }
}

}  // namespace stiction::plot
