#include "render/inset_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plot/figure.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {
namespace {

// The plot is laid out as a print figure at this many pixels per inch, so its text has a size
// in pixels chosen for the video (font_px) rather than one scaled down from 1600 x 1000.
constexpr double kDpi = 108.0;
constexpr int kMinWidth = 200, kMinHeight = 150;  // plot::draw's least figure size
constexpr image::Rgba kCursor{200, 30, 30, 255};

// The signal's values: its column, or the norm of its axis columns (as the overlay shows it).
std::vector<double> signal_values(const core::Trajectory& trajectory, const std::string& name) {
  std::vector<int> columns;
  if (const auto c = trajectory.find(name)) {
    columns.push_back(*c);
  } else {
    for (int c = 0; c < trajectory.column_count(); ++c) {
      if (is_axis_of(trajectory.columns()[static_cast<std::size_t>(c)], name)) columns.push_back(c);
    }
  }
  if (columns.empty()) {
    std::string message = "[inset] signals: no signal named '";
    message.append(name).append("'");
    throw RenderError(message);
  }
  std::vector<double> values(static_cast<std::size_t>(trajectory.row_count()));
  for (int r = 0; r < trajectory.row_count(); ++r) {
    if (columns.size() == 1) {
      values[static_cast<std::size_t>(r)] = trajectory.at(r, columns[0]);
      continue;
    }
    double sum = 0.0;
    for (int c : columns) sum += trajectory.at(r, c) * trajectory.at(r, c);
    values[static_cast<std::size_t>(r)] = std::sqrt(sum);
  }
  return values;
}

// `source` resized to w x h (not larger) by averaging the source pixels under each pixel: a
// white background stays exactly white, so the inset's translucency still finds it.
image::Image shrunk(const image::Image& source, int w, int h) {
  image::Image out(w, h);
  for (int y = 0; y < h; ++y) {
    const int sy0 = y * source.height / h, sy1 = std::max(sy0 + 1, (y + 1) * source.height / h);
    for (int x = 0; x < w; ++x) {
      const int sx0 = x * source.width / w, sx1 = std::max(sx0 + 1, (x + 1) * source.width / w);
      int sum[4] = {0, 0, 0, 0};
      for (int v = sy0; v < sy1; ++v) {
        for (int u = sx0; u < sx1; ++u) {
          const std::uint8_t* p = source.data(u, v);
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
        }
      }
      const int n = (sy1 - sy0) * (sx1 - sx0);
      std::uint8_t* d = out.data(x, y);
      for (int c = 0; c < 4; ++c) d[c] = static_cast<std::uint8_t>(sum[c] / n);
    }
  }
  return out;
}

// The events worth a mark in a small plot: the changes between slipping and sticking. A
// contact that chatters (opens and touches down every few milliseconds, as sphere_roll's
// bouncing start does) gives dozens of "open" events and re-sticks that would bury the one
// transition the viewer is to see; those are left out. Events of unknown kind all stay.
std::vector<InsetEvent> regime_changes(std::vector<InsetEvent> events) {
  std::stable_sort(events.begin(), events.end(),
                   [](const InsetEvent& a, const InsetEvent& b) { return a.time < b.time; });
  std::vector<InsetEvent> out;
  std::string last;
  for (const InsetEvent& e : events) {
    if (e.kind.empty()) {
      out.push_back(e);
      continue;
    }
    if (e.kind == "open" || e.kind == last) continue;
    out.push_back(e);
    last = e.kind;
  }
  return out;
}

}  // namespace

InsetPlot::InsetPlot(const InsetSettings& settings, const core::Trajectory& trajectory,
                     int frame_width, int frame_height, std::vector<InsetEvent> events,
                     int reserved_bottom)
    : settings_(settings), events_(regime_changes(std::move(events))) {
  if (trajectory.row_count() == 0) throw RenderError("[inset]: the run has no rows");
  times_ = trajectory.column(0);
  start_ = times_.front();
  end_ = std::max(times_.back(), start_ + 1e-9);
  for (const std::string& s : settings_.signals) {
    values_.push_back(signal_values(trajectory, s));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : values_.back()) {
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    ranges_.emplace_back(lo, hi);
  }
  // Text a little smaller than the overlay's (height / 30), readable at 720p and 360p.
  font_px_ = std::clamp(frame_height / 48.0, 9.0, 22.0);
  int w =
      settings_.in_pixels ? int(settings_.width) : int(std::lround(settings_.width * frame_width));
  int h = settings_.in_pixels ? int(settings_.height)
                              : int(std::lround(settings_.height * frame_height));
  // The inset stays inside the frame (less its margin); a box too small for a figure (a
  // tile of a compare video) gets the figure drawn at the least size, same aspect, and
  // scaled down once per page.
  const int margin = std::max(2, frame_height / 60);
  w = std::clamp(w, 8, std::max(8, frame_width - 2 * margin));
  h = std::clamp(h, 8, std::max(8, frame_height - 2 * margin));
  const double enlarge = std::max({1.0, double(kMinWidth) / w, double(kMinHeight) / h});
  figure_width_ = static_cast<int>(std::ceil(w * enlarge));
  figure_height_ = static_cast<int>(std::ceil(h * enlarge));
  font_px_ *= enlarge;
  if (w > frame_width || h > frame_height) {
    throw RenderError("[inset]: the frame is too small for an inset");
  }
  const bool left =
      settings_.corner == InsetCorner::top_left || settings_.corner == InsetCorner::bottom_left;
  const bool top =
      settings_.corner == InsetCorner::top_left || settings_.corner == InsetCorner::top_right;
  box_.x0 = left ? std::min(margin, frame_width - w) : std::max(0, frame_width - margin - w);
  box_.y0 = top ? std::min(margin, frame_height - h)
                : std::max(0, frame_height - margin - std::max(0, reserved_bottom) - h);
  box_.x1 = box_.x0 + w;
  box_.y1 = box_.y0 + h;
}

std::pair<double, double> InsetPlot::page_range(double t) {
  const Page& p = page(t);
  return {p.t0, p.t1};
}

const plot::FigureLayout& InsetPlot::drawn_layout(double t) { return page(t).drawn; }

const InsetPlot::Page& InsetPlot::page(double t) {
  int index = 0;
  double t0 = start_, t1 = end_;
  if (settings_.window && *settings_.window < end_ - start_) {
    const double w = *settings_.window;
    // In doubles until clamped: a tiny window over a long run has more pages than an int.
    const double last = std::max(0.0, std::ceil((end_ - start_) / w - 1e-9) - 1.0);
    const double at = std::clamp(std::floor((t - start_) / w), 0.0, std::min(last, 1e9));
    index = static_cast<int>(at);
    t0 = start_ + index * w;
    t1 = t0 + w;
  }
  if (page_.index != index) {
    page_.index = index;
    page_.t0 = t0;
    page_.t1 = t1;
    draw_page(page_);
  }
  return page_;
}

void InsetPlot::draw_page(Page& page) const {
  plot::Figure figure;
  figure.x_label = "t";
  figure.x_unit = "s";
  figure.x_min = page.t0;
  figure.x_max = page.t1;
  plot::Figure::Print print;
  print.dpi = kDpi;
  print.width_mm = figure_width_ * 25.4 / kDpi;
  print.height_mm = figure_height_ * 25.4 / kDpi;
  print.font_pt = font_px_ * 72.0 / kDpi;
  figure.print = print;
  // Only the rows of this page (and one on each side, so the line reaches the frame's edges).
  const auto first = std::lower_bound(times_.begin(), times_.end(), page.t0);
  const auto last = std::upper_bound(times_.begin(), times_.end(), page.t1);
  const std::size_t r0 = first == times_.begin() ? 0 : std::size_t(first - times_.begin()) - 1;
  const std::size_t r1 = std::min(times_.size(), std::size_t(last - times_.begin()) + 1);
  for (std::size_t i = 0; i < settings_.signals.size(); ++i) {
    plot::Panel& panel = figure.panels.emplace_back();
    panel.label = i < settings_.labels.size() ? settings_.labels[i] : settings_.signals[i];
    panel.unit = i < settings_.units.size() ? settings_.units[i] : "";
    // The whole run's range on every page, so the scale does not jump when the page turns;
    // an empty series keeps it in the axes image too, which must match the curves' axes.
    const auto [lo, hi] = ranges_[i];
    if (std::isfinite(lo) && std::isfinite(hi)) {
      const double pad = hi > lo ? 0.05 * (hi - lo) : std::max(1e-9, 0.05 * std::abs(hi));
      panel.y_min = lo - pad;
      panel.y_max = hi + pad;
    }
    plot::Series series;
    series.style = plot::series_style(static_cast<int>(i));
    series.style->width = 5.0;
    series.style->dash.clear();  // a thin dash pattern reads as noise at video size
    series.x.assign(times_.begin() + static_cast<std::ptrdiff_t>(r0),
                    times_.begin() + static_cast<std::ptrdiff_t>(r1));
    series.y.assign(values_[i].begin() + static_cast<std::ptrdiff_t>(r0),
                    values_[i].begin() + static_cast<std::ptrdiff_t>(r1));
    panel.series.push_back(std::move(series));
  }
  for (const InsetEvent& e : events_) {
    if (e.time < page.t0 || e.time > page.t1) continue;
    plot::EventMarker m;
    m.x = e.time;
    m.kind = e.kind;
    m.label = e.kind;
    figure.events.push_back(m);
  }
  // Labels only while few enough to read in a corner of the video; else unlabelled marks.
  for (plot::EventMarker& m : figure.events)
    m.labelled = !m.kind.empty() && figure.events.size() <= 4;
  page.full = plot::render(figure, &page.layout);
  page.drawn = page.layout;
  for (plot::Panel& panel : figure.panels) {
    for (plot::Series& s : panel.series) {
      s.x.clear();
      s.y.clear();
    }
  }
  plot::FigureLayout axes_layout;
  page.axes = plot::render(figure, &axes_layout);
  const int w = box_.x1 - box_.x0, h = box_.y1 - box_.y0;
  if (page.full.width != w || page.full.height != h) {
    const double sx = double(w) / page.full.width, sy = double(h) / page.full.height;
    page.full = shrunk(page.full, w, h);
    page.axes = shrunk(page.axes, w, h);
    for (plot::Rect& r : page.layout.panels) r = {r.x0 * sx, r.y0 * sy, r.x1 * sx, r.y1 * sy};
  }
}

double InsetPlot::column_of(const Page& page, double t) const {
  const plot::Rect& panel = page.layout.panels.front();
  const plot::AxisRange& x = page.layout.x_axis;
  const double u = std::clamp((t - x.lo) / (x.hi - x.lo), 0.0, 1.0);
  return panel.x0 + u * panel.width();
}

int InsetPlot::cursor_x(double t) {
  const Page& p = page(t);
  return box_.x0 + static_cast<int>(std::floor(column_of(p, t)));
}

PixelBox InsetPlot::panels_box(double t) {
  const Page& p = page(t);
  PixelBox b;
  b.x0 = box_.x0 + static_cast<int>(std::floor(p.layout.panels.front().x0));
  b.x1 = box_.x0 + static_cast<int>(std::ceil(p.layout.panels.front().x1));
  b.y0 = box_.y0 + static_cast<int>(std::floor(p.layout.panels.front().y0));
  b.y1 = box_.y0 + static_cast<int>(std::ceil(p.layout.panels.back().y1));
  return b;
}

void InsetPlot::draw(image::Image& frame, double t) {
  const Page& p = page(t);
  const int cut = static_cast<int>(std::floor(column_of(p, t)));  // inset column of the cursor
  const int w = std::min(p.full.width, box_.x1 - box_.x0);
  const int h = std::min(p.full.height, box_.y1 - box_.y0);
  // Background (pure white in the plot) blended at `opacity`; everything else opaque.
  const int a = static_cast<int>(std::lround(settings_.opacity * 256.0));
  const PixelBox panels = panels_box(t);
  for (int y = 0; y < h; ++y) {
    std::uint8_t* dst = frame.data(box_.x0, box_.y0 + y);
    const std::uint8_t* curves = p.full.data(0, y);
    const std::uint8_t* axes = p.axes.data(0, y);
    for (int x = 0; x < w; ++x, dst += 4, curves += 4, axes += 4) {
      const std::uint8_t* src = x < cut ? curves : axes;
      if (src[0] == 255 && src[1] == 255 && src[2] == 255) {
        for (int c = 0; c < 3; ++c)
          dst[c] = static_cast<std::uint8_t>(dst[c] + (((255 - dst[c]) * a) >> 8));
      } else {
        dst[0] = src[0];
        dst[1] = src[1];
        dst[2] = src[2];
      }
    }
  }
  // The cursor: two pixels wide, over every panel.
  for (int y = panels.y0; y < panels.y1; ++y) {
    for (int x = box_.x0 + cut - 1; x <= box_.x0 + cut; ++x) {
      if (x >= box_.x0 && x < box_.x0 + w) frame.set(x, y, kCursor);
    }
  }
}

}  // namespace stiction::render
