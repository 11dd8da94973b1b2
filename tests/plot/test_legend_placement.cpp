// A legend avoids the data: inside the axes where it covers the least, when that is a small
// share of the panel's data (measured here by rasterizing the series alone, independently of
// the figure's own placement code), else above the panel or beside the axes, never over a
// frame. Tested on generated figures:
// 1..8 series of random shapes per panel, random sizes, pixel and print designs.
#include <cairo.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "plot/figure.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "legends";

double map(const plot::AxisRange& a, double v, double p_lo, double p_hi) {
  double u = v, lo = a.lo, hi = a.hi;
  if (a.log) {
    if (!(v > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    u = std::log10(v);
    lo = std::log10(lo);
    hi = std::log10(hi);
  }
  return p_lo + (u - lo) / (hi - lo) * (p_hi - p_lo);
}

// Pixels a series' stroke inks, plus one pixel around it: every series of `panel` drawn as a
// plain polyline at its width + 2 px (a dense band lies inside its polyline's ink).
long ink_under(const plot::Figure& figure, const plot::FigureLayout& layout, int panel,
               const plot::Rect& box) {
  const plot::Rect& f = layout.panels[panel];
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_A8, layout.width, layout.height),
      &cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                        &cairo_destroy);
  cairo_rectangle(cr.get(), f.x0, f.y0, f.width(), f.height());
  cairo_clip(cr.get());
  const double scale = figure.print ? 0.3 * figure.print->dpi / 72.0
                                    : std::min(layout.width / 1600.0, layout.height / 1000.0);
  const plot::Panel& p = figure.panels[panel];
  for (std::size_t i = 0; i < p.series.size(); ++i) {
    const plot::Series& s = p.series[i];
    const plot::LineStyle style = s.style ? *s.style : plot::series_style(static_cast<int>(i));
    cairo_set_line_width(cr.get(), style.width * scale + 2.0);
    cairo_set_line_cap(cr.get(), CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr.get(), CAIRO_LINE_JOIN_ROUND);
    bool open = false;
    for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
      const double x = map(layout.x_axis, s.x[k], f.x0, f.x1);
      const double y = map(layout.y_axes[panel], s.y[k], f.y1, f.y0);
      if (!std::isfinite(x) || !std::isfinite(y)) {
        open = false;
        continue;
      }
      if (open) {
        cairo_line_to(cr.get(), x, y);
      } else {
        cairo_move_to(cr.get(), x, y);
        open = true;
      }
    }
    cairo_stroke(cr.get());
  }
  cairo_surface_flush(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  long inked = 0;
  for (int y = std::max(0, static_cast<int>(box.y0));
       y < std::min(layout.height, static_cast<int>(box.y1)); ++y) {
    for (int x = std::max(0, static_cast<int>(box.x0));
         x < std::min(layout.width, static_cast<int>(box.x1)); ++x) {
      inked += data[static_cast<std::size_t>(y) * stride + x] != 0 ? 1 : 0;
    }
  }
  return inked;
}

// A random series shape over [0, duration].
plot::Series random_series(std::mt19937& rng, double duration, int index) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  plot::Series s;
  const int shape = static_cast<int>(7 * unit(rng));
  const double a = 0.2 + 3 * unit(rng), b = 4 * (unit(rng) - 0.5), w = 0.5 + 8 * unit(rng),
               phase = 6.3 * unit(rng);
  const int samples = 200 + static_cast<int>(1800 * unit(rng));
  for (int k = 0; k <= samples; ++k) {
    const double t = duration * k / samples;
    double y = 0.0;
    switch (shape) {
      case 0:
        y = b + a * std::sin(w * t + phase);
        break;
      case 1:
        y = b + (t > duration * unit(rng) * 0.0 + duration * 0.4 ? a : -a);  // a step
        break;
      case 2:
        y = b + a * t / duration;  // a ramp
        break;
      case 3:
        y = b;  // a constant
        break;
      case 4:
        y = b + a * (unit(rng) - 0.5);  // noise
        break;
      case 5:
        y = b + a * std::sin(300.0 * t);  // dense
        break;
      default:
        y = b + a * std::exp(-w * t / duration);  // a decay
    }
    if (shape == 0 && k > samples / 3 && k < samples / 3 + 20) y = std::nan("");  // a gap
    s.x.push_back(t);
    s.y.push_back(y);
  }
  s.label =
      "series " + std::to_string(index) + std::string(static_cast<std::size_t>(8 * unit(rng)), 'x');
  return s;
}

}  // namespace

TEST_CASE("legends go inside where they cover the least data, else outside the axes",
          "[plot][legend]") {
  std::mt19937 rng(606);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  fs::create_directories(kOut);
  double worst = 0.0;
  int inside = 0, outside = 0;
  for (int i = 0; i < 60; ++i) {
    plot::Figure figure;
    if (unit(rng) < 0.3) {
      figure.print = plot::Figure::Print{70 + 110 * unit(rng), 50 + 80 * unit(rng),
                                         7 + 3 * unit(rng), 150 + 250 * unit(rng)};
    } else {
      figure.width = 500 + static_cast<int>(1900 * unit(rng));
      figure.height = 400 + static_cast<int>(1200 * unit(rng));
    }
    const double duration = 1 + 10 * unit(rng);
    const int panels = 1 + static_cast<int>(3 * unit(rng));
    for (int p = 0; p < panels; ++p) {
      plot::Panel& panel = figure.panels.emplace_back();
      panel.label = "quantity " + std::to_string(p);
      panel.unit = "m";
      const int n = 1 + static_cast<int>(8 * unit(rng));
      for (int k = 0; k < n; ++k) panel.series.push_back(random_series(rng, duration, k));
    }
    plot::FigureLayout layout;
    if (i < 8 || i == 9 || i == 34 || i == 54) {
      layout = plot::write_figure(figure, kOut / ("random_" + std::to_string(i) + ".png"),
                                  plot::Format::png);
    } else {
      plot::render(figure, &layout);
    }
    INFO("figure " << i << ", " << layout.width << " x " << layout.height);
    const std::vector<std::string> problems = plot::layout_problems(layout);
    for (const std::string& p : problems) UNSCOPED_INFO(p);
    CHECK(problems.empty());
    REQUIRE(layout.legend_panels.size() == layout.legends.size());
    for (std::size_t k = 0; k < layout.legends.size(); ++k) {
      const plot::Rect& box = layout.legends[k];
      const int p = layout.legend_panels[k];
      if (layout.legend_outside[k]) {
        ++outside;
        for (const plot::Rect& f : layout.panels) CHECK_FALSE(box.overlaps(f));
        continue;
      }
      ++inside;
      CHECK(box.inside(layout.panels[p]));
      // At most a small share of the panel's data under it (the placement allows 2% of the
      // data as it draws it; this rasterization is 2 px wider, so a little more).
      const long inked = ink_under(figure, layout, p, box);
      const long data = ink_under(figure, layout, p, layout.panels[p]);
      const double share = data > 0 ? static_cast<double>(inked) / static_cast<double>(data) : 0.0;
      worst = std::max(worst, share);
      INFO("legend over " << inked << " of the panel's " << data << " data pixels");
      CHECK(share <= 0.05);
    }
  }
  CHECK(inside > 0);
  CHECK(outside > 0);
  WARN("legends inside " << inside << ", outside " << outside
                         << "; the largest share of a panel's data under a legend inside: "
                         << worst);
}

// A legend never covers data, even where no corner of a panel is free and the page leaves no
// room above or beside the axes: it then goes outside all the same (the caption row, above
// in as many rows as it takes) rather than over the data. Fig. 7's torque panel is the case
// reported: two motor torques dithering over a band that fills the panel from 4 s on, with
// a reference line, squeezed onto small pages with a four-row column of event labels.
TEST_CASE("a legend covers no data when no corner is free", "[plot][legend]") {
  fs::create_directories(kOut);
  int inside = 0, outside = 0, figures = 0, left_out = 0;
  for (const double width_mm : {70.0, 80.0, 88.0, 100.0, 120.0}) {
    for (const double height_mm : {50.0, 60.0, 70.0, 85.0, 100.0}) {
      plot::Figure figure;
      figure.title = "Two-link arm, joint friction (cf. paper Fig. 7)";
      figure.print = plot::Figure::Print{width_mm, height_mm, 8.0, 300.0};
      figure.panels.resize(2);
      plot::Panel& angles = figure.panels[0];
      angles.label = "Joint angle θ";
      angles.unit = "rad";
      plot::Panel& torques = figure.panels[1];
      torques.label = "Motor torque";
      torques.unit = "N·m";
      torques.references.push_back(plot::ReferenceLine{0.5, "friction level F"});
      for (int j = 0; j < 2; ++j) {
        plot::Series angle, torque;
        angle.label = torque.label = "joint " + std::to_string(j);
        for (int k = 0; k <= 4000; ++k) {
          const double t = 20.0 * k / 4000;
          angle.x.push_back(t);
          angle.y.push_back(std::clamp(t - 1.0 - j, 0.0, 3.6) * (j ? 2.1 : 3.6));
          torque.x.push_back(t);
          // A ramp to the friction level, held, then dithering over [0.2, 0.48] from 4 s.
          torque.y.push_back(t < 4.0 ? std::min(0.52, 0.3 * t * (j ? 1.2 : 1.0))
                                     : (k % 2 == j ? 0.48 : 0.2));
        }
        angles.series.push_back(std::move(angle));
        torques.series.push_back(std::move(torque));
      }
      for (const double t : {1.005, 1.571, 4.636, 4.651}) {
        plot::EventMarker e;
        e.x = t;
        e.label = "joint1_friction slip " + std::to_string(t).substr(0, 5) + " s";
        e.kind = "slip";
        figure.events.push_back(e);
      }
      const std::string name = "crowded_" + std::to_string(static_cast<int>(width_mm)) + "x" +
                               std::to_string(static_cast<int>(height_mm));
      const plot::FigureLayout layout =
          plot::write_figure(figure, kOut / (name + ".png"), plot::Format::png);
      ++figures;
      INFO(name);
      for (std::size_t k = 0; k < layout.legends.size(); ++k) {
        const plot::Rect& box = layout.legends[k];
        const int p = layout.legend_panels[k];
        if (layout.legend_outside[k]) {
          ++outside;
          for (const plot::Rect& f : layout.panels) CHECK_FALSE(box.overlaps(f));
          continue;
        }
        ++inside;
        const long inked = ink_under(figure, layout, p, box);
        const long data = ink_under(figure, layout, p, layout.panels[p]);
        INFO("legend of panel " << p << " over " << inked << " of " << data << " data pixels");
        CHECK(static_cast<double>(inked) <= 0.05 * static_cast<double>(data));
      }
      // From 70 mm high every panel's legend is shown somewhere; on smaller pages one may be
      // left out (and reported) rather than drawn over the data.
      if (height_mm >= 70.0) {
        CHECK(layout.legends.size() == 2);
        CHECK(layout.legends_left_out.empty());
      } else {
        left_out += static_cast<int>(layout.legends_left_out.size());
      }
    }
  }
  WARN(figures << " figures: legends inside " << inside << ", outside " << outside << ", left out "
               << left_out);
}

// A legend entry already in an earlier panel's legend (same label, same line) is not
// repeated: Fig. 7's torque panel keeps "friction level F" alone, and a panel whose entries
// are all in the legend above has none. An entry that would be left alone without a
// reference line keeps its panel's legend whole.
TEST_CASE("legend entries shown in an earlier panel are not repeated", "[plot][legend]") {
  auto series = [](const std::string& label, double gain) {
    plot::Series s;
    s.label = label;
    for (int k = 0; k <= 200; ++k) {
      s.x.push_back(0.01 * k);
      s.y.push_back(gain * std::sin(0.03 * k));
    }
    return s;
  };
  plot::Figure figure;
  figure.print = plot::Figure::Print{88.0, 100.0, 8.0, 300.0};
  figure.panels.resize(4);
  const char* names[] = {"angle", "torque", "rate", "error"};
  for (int p = 0; p < 4; ++p) figure.panels[p].label = names[p];
  for (int p = 0; p < 3; ++p) {
    figure.panels[p].series.push_back(series("joint 0", 1.0 + p));
    figure.panels[p].series.push_back(series("joint 1", -1.0 - p));
  }
  figure.panels[1].references.push_back(plot::ReferenceLine{0.5, "friction level F"});
  // joint 0 as above, and a new series: the legend keeps both.
  figure.panels[3].series.push_back(series("joint 0", 2.0));
  figure.panels[3].series.push_back(series("joint 2", 0.5));
  const plot::FigureLayout layout =
      plot::write_figure(figure, kOut / "shared_entries.png", plot::Format::png);
  std::vector<std::vector<std::string>> entries(4);
  for (const plot::TextBox& t : layout.texts) {
    if (t.role == plot::TextRole::legend_entry && t.panel >= 0) entries[t.panel].push_back(t.given);
  }
  CHECK(entries[0] == std::vector<std::string>{"joint 0", "joint 1"});
  CHECK(entries[1] == std::vector<std::string>{"friction level F"});
  CHECK(entries[2].empty());
  CHECK(entries[3] == std::vector<std::string>{"joint 0", "joint 2"});
  CHECK(plot::layout_problems(layout).empty());
}
