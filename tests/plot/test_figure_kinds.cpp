// Every kind of figure the code makes, with long generated labels (titles, axis labels,
// units, legend entries, captions, run and element names, event labels): a run's figures
// (the default figures and a [[plots]]-like spec), verify's figures (events by name), a
// comparison of runs (the default and --signals), study's work-precision plot and the
// video's inset. In each: no text is cut inside a word (every word drawn is a whole word of
// what was given: text_fit.hpp leaves out whole words only), no text leaves the figure, and
// a legend inside a panel covers at most a small share of its data (rasterized here, apart
// from the placement code: each series a polyline 2 px wider than drawn).
#include <cairo.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/column_info.hpp"
#include "image/png.hpp"
#include "plot/plot_spec.hpp"
#include "render/inset_plot.hpp"
#include "services/study.hpp"
#include "word_runs.hpp"

using namespace stiction;
namespace fs = std::filesystem;

using stiction::testing::word_runs;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "figure_kinds";

// Words for generated labels: long enough that a cut piece of one is not another.
const std::vector<std::string> kWords{
    "horizontal",   "velocity",    "friction",   "contact",     "element",  "centre",
    "acceleration", "normal",      "tangential", "spring",      "damper",   "reference",
    "shoulder",     "elbow",       "wrist",      "torque",      "angle",    "position",
    "rolling",      "sliding",     "anchor",     "offset",      "relative", "measured",
    "pendulum",     "conveyor",    "platform",   "actuator",    "gearbox",  "bearing",
    "trajectory",   "stiffness",   "damping",    "coulomb",     "stribeck", "viscous",
    "quaternion",   "orientation", "rotation",   "translation", "left",     "right",
    "front",        "rear",        "upper",      "lower",       "inner",    "outer"};

class Generator {
 public:
  explicit Generator(unsigned seed) : rng_(seed) {}
  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  std::string word() {
    return kWords[static_cast<std::size_t>(below(static_cast<int>(kWords.size())))];
  }
  // An identifier of `n` words joined by '_'.
  std::string name(int n) {
    std::string s = word();
    for (int i = 1; i < n; ++i) s += "_" + word();
    return s;
  }
  // A phrase of 1..max words, sometimes with a remark in parentheses.
  std::string phrase(int max) {
    std::string s = word();
    for (int i = 1 + below(max); i > 1; --i) s += " " + word();
    if (below(3) == 0) s += " (" + word() + " " + word() + ")";
    return s;
  }
  std::string unit() {
    static const std::vector<std::string> units{"m/s", "N\u00B7m", "rad", "m", "N", "rad/s", "1"};
    return units[static_cast<std::size_t>(below(static_cast<int>(units.size())))];
  }
  plot::Figure::Print print() {
    return plot::Figure::Print{uniform(70.0, 120.0), uniform(55.0, 110.0), uniform(6.0, 9.0),
                               below(2) ? 300.0 : 150.0};
  }

 private:
  std::mt19937 rng_;
};

// Everything the figure was given to say, as words.
std::set<std::string> corpus(const plot::Figure& figure) {
  std::set<std::string> words{"10"};  // "×10ⁿ" factors of an axis
  auto add = [&](const std::string& text) {
    for (const std::string& w : word_runs(text)) words.insert(w);
  };
  add(figure.title);
  add(figure.x_label);
  add(figure.x_unit);
  for (const plot::Panel& p : figure.panels) {
    add(p.label);
    add(p.unit);
    add(p.caption);
    for (const plot::Series& s : p.series) add(s.label);
    for (const plot::ReferenceLine& r : p.references) add(r.label);
  }
  for (const plot::EventMarker& e : figure.events) add(e.label + " " + e.kind);
  for (const char* key : {"stick", "slip", "slide", "tip", "lift", "off", "land", "touch", "down",
                          "open", "partial"}) {
    words.insert(key);  // the key of the event marks
  }
  return words;
}

// Pixels of `panel`'s series as polylines 2 px wider than drawn, under `box` and in all.
struct Ink {
  long under = 0, total = 0;
};
Ink series_ink(const plot::Figure& figure, const plot::FigureLayout& layout, int panel,
               const plot::Rect& box) {
  const plot::Rect& f = layout.panels[static_cast<std::size_t>(panel)];
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_A8, layout.width, layout.height),
      &cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                        &cairo_destroy);
  cairo_rectangle(cr.get(), f.x0, f.y0, f.width(), f.height());
  cairo_clip(cr.get());
  const double line = figure.print ? 0.3 * figure.print->dpi / 72.0
                                   : std::min(layout.width / 1600.0, layout.height / 1000.0);
  const plot::AxisRange& xa = layout.x_axis;
  const plot::AxisRange& ya = layout.y_axes[static_cast<std::size_t>(panel)];
  auto map = [](const plot::AxisRange& a, double v, double p0, double p1) {
    double u = v, lo = a.lo, hi = a.hi;
    if (a.log) {
      if (!(v > 0.0)) return std::nan("");
      u = std::log10(v);
      lo = std::log10(lo);
      hi = std::log10(hi);
    }
    return p0 + (u - lo) / (hi - lo) * (p1 - p0);
  };
  const plot::Panel& p = figure.panels[static_cast<std::size_t>(panel)];
  for (std::size_t i = 0; i < p.series.size(); ++i) {
    const plot::Series& s = p.series[i];
    const plot::LineStyle style = s.style ? *s.style : plot::series_style(static_cast<int>(i));
    cairo_set_line_width(cr.get(), style.width * line + 2.0);
    cairo_set_line_cap(cr.get(), CAIRO_LINE_CAP_ROUND);
    bool open = false;
    for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
      const double x = map(xa, s.x[k], f.x0, f.x1), y = map(ya, s.y[k], f.y1, f.y0);
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
  Ink ink;
  for (int y = 0; y < layout.height; ++y) {
    for (int x = 0; x < layout.width; ++x) {
      if (data[static_cast<std::size_t>(y) * stride + x] == 0) continue;
      ++ink.total;
      if (x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1) ++ink.under;
    }
  }
  return ink;
}

struct Tally {
  int figures = 0, texts = 0, shortened = 0, legends_inside = 0, legends_outside = 0;
};

// The three checks on one figure as drawn.
void check(const plot::Figure& figure, const plot::FigureLayout& layout, const std::string& name,
           Tally& tally, bool legends = true) {
  INFO(name);
  ++tally.figures;
  const std::set<std::string> given = corpus(figure);
  const plot::Rect page{0.0, 0.0, static_cast<double>(layout.width),
                        static_cast<double>(layout.height)};
  for (const plot::TextBox& t : layout.texts) {
    ++tally.texts;
    if (t.text.find("\u2026") != std::string::npos) ++tally.shortened;
    // Inside the figure (half a pixel of rounding).
    const plot::Rect in{t.box.x0 + 0.5, t.box.y0 + 0.5, t.box.x1 - 0.5, t.box.y1 - 0.5};
    INFO("text '" << t.text << "' at [" << t.box.x0 << ", " << t.box.y0 << ", " << t.box.x1 << ", "
                  << t.box.y1 << "]");
    CHECK(in.inside(page));
    if (t.role == plot::TextRole::tick_label) continue;  // numbers, never shortened
    for (const std::string& w : word_runs(t.text)) {
      INFO("word '" << w << "'");
      CHECK(given.count(w) == 1);
    }
  }
  for (const std::string& problem : plot::layout_problems(layout)) {
    // Overlaps are the layout tests' (test_layouts, test_print_size); here: nothing leaves
    // the figure and no legend is left out.
    const bool escape = problem.rfind("outside the image", 0) == 0 ||
                        problem.find("leaves the image") != std::string::npos ||
                        problem.find("has no room") != std::string::npos;
    INFO(problem);
    CHECK_FALSE(escape);
  }
  if (!legends) return;
  for (std::size_t l = 0; l < layout.legends.size(); ++l) {
    if (layout.legend_outside[l]) {
      ++tally.legends_outside;
      continue;
    }
    ++tally.legends_inside;
    const Ink ink = series_ink(figure, layout, layout.legend_panels[l], layout.legends[l]);
    INFO("legend " << l << " of panel " << layout.legend_panels[l] << ": " << ink.under << " of "
                   << ink.total << " data pixels under it");
    CHECK(static_cast<double>(ink.under) <= 0.05 * static_cast<double>(ink.total) + 4.0);
  }
}

void save(const image::Image& img, const std::string& name) {
  fs::create_directories(kOut);
  image::write_png(kOut / (name + ".png"), img, image::PngSpeed::fast);
}

// A run of `columns` (first "t") with smooth generated signals over `duration`.
core::Trajectory generated_run(Generator& g, const std::vector<std::string>& columns,
                               double duration) {
  core::Trajectory tr(columns);
  std::vector<double> amplitude, frequency, phase, offset;
  for (std::size_t c = 1; c < columns.size(); ++c) {
    amplitude.push_back(std::pow(10.0, g.uniform(-3.0, 3.0)));
    frequency.push_back(g.uniform(0.3, 4.0));
    phase.push_back(g.uniform(0.0, 6.28));
    offset.push_back(g.uniform(-1.0, 1.0));
  }
  std::vector<double> row(columns.size());
  for (int i = 0; i <= 600; ++i) {
    row[0] = duration * i / 600.0;
    for (std::size_t c = 1; c < columns.size(); ++c) {
      const double t = row[0];
      row[c] = amplitude[c - 1] *
               (offset[c - 1] + std::sin(frequency[c - 1] * t + phase[c - 1]) * std::exp(-0.1 * t));
    }
    tr.append(row.data());
  }
  return tr;
}

// A scene's worth of columns: elements with long names, each a vector signal and a scalar.
struct GeneratedScene {
  std::vector<core::ColumnInfo> columns;
  std::vector<std::string> elements;
};
GeneratedScene generated_scene(Generator& g) {
  GeneratedScene s;
  s.columns.push_back({"t", "s", "", "time"});
  const int elements = 1 + g.below(3);
  for (int e = 0; e < elements; ++e) {
    const std::string element = g.name(1 + g.below(5));
    s.elements.push_back(element);
    const std::string vector_signal = g.word(), scalar = g.word() + "_" + g.word();
    const std::string unit = g.unit();
    for (const char* axis : {"x", "y", "z"}) {
      s.columns.push_back({element + "." + vector_signal + "." + axis, unit, "world", g.phrase(8)});
    }
    s.columns.push_back({element + "." + scalar, g.unit(), "", g.phrase(10)});
  }
  return s;
}

std::vector<std::string> names_of(const std::vector<core::ColumnInfo>& columns) {
  std::vector<std::string> names;
  for (const core::ColumnInfo& c : columns) names.push_back(c.name);
  return names;
}

}  // namespace

TEST_CASE(
    "figures of every kind with long generated labels: whole words, inside, legends "
    "off the data",
    "[plot][figure-kinds]") {
  Tally tally;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    Generator g(seed);
    const GeneratedScene scene = generated_scene(g);
    const double duration = g.uniform(0.5, 20.0);
    const core::Trajectory run = generated_run(g, names_of(scene.columns), duration);
    std::vector<plot::PlotEvent> events;
    std::map<std::string, double> event_times;
    for (const std::string& element : scene.elements) {
      for (int k = 0; k < 1 + g.below(4); ++k) {
        const double t = g.uniform(0.05, 0.95) * duration;
        const std::string kind = k % 2 ? "slip" : "stick";
        events.push_back({element, kind, t});
        event_times[element + "." + kind + "_time"] = t;
      }
    }
    std::sort(events.begin(), events.end(),
              [](const plot::PlotEvent& a, const plot::PlotEvent& b) { return a.time < b.time; });
    const std::string stem = "seed" + std::to_string(seed);

    // A run's default figures, on their own page and on a generated one.
    for (const plot::PlotSpec& spec : plot::default_plot_specs(scene.columns)) {
      plot::Figure figure = plot::make_figure(spec, run, events);
      for (int page = 0; page < 2; ++page) {
        if (page == 1) figure.print = g.print();
        plot::FigureLayout layout;
        const image::Image img = plot::render(figure, &layout);
        const std::string name = stem + "_run_" + spec.name + (page ? "_page" : "");
        save(img, name);
        check(figure, layout, name, tally);
      }
    }

    // A [[plots]]-like spec: long title, labels, legends and references.
    plot::PlotSpec custom;
    custom.name = "custom";
    custom.title = g.phrase(14);
    for (int p = 0; p < 1 + g.below(3); ++p) {
      plot::PanelSpec panel;
      // Up to four signals in a panel, as a scene's [[plots]] would have.
      for (std::size_t c = 1; c < scene.columns.size() && panel.signals.size() < 4; ++c) {
        if (g.below(3) == 0 || panel.signals.empty()) {
          panel.signals.push_back(scene.columns[c].name);
          panel.legend.push_back(g.phrase(6));
        }
      }
      panel.label = g.phrase(7);
      panel.unit = g.unit();
      if (g.below(2)) panel.references.push_back({0.0, g.phrase(4)});
      custom.panels.push_back(panel);
    }
    custom.print = plot::PrintSize{g.uniform(70.0, 120.0), g.uniform(60.0, 110.0), 8.0};
    {
      const plot::Figure figure = plot::make_figure(custom, run, events);
      plot::FigureLayout layout;
      const image::Image img = plot::render(figure, &layout);
      save(img, stem + "_custom");
      check(figure, layout, stem + "_custom", tally);
    }

    // verify's figures: the same specs with the events by name.
    for (const plot::PlotSpec& spec : plot::default_plot_specs(scene.columns)) {
      const plot::Figure figure = plot::make_figure(spec, run, event_times);
      plot::FigureLayout layout;
      plot::render(figure, &layout);
      check(figure, layout, stem + "_verify_" + spec.name, tally);
    }

    // Comparisons: long run names, the default and chosen signals.
    const core::Trajectory other = generated_run(g, names_of(scene.columns), duration);
    const core::Trajectory third = generated_run(g, names_of(scene.columns), duration);
    std::vector<plot::Run> runs{{g.name(2 + g.below(3)), &run}, {g.name(1 + g.below(4)), &other}};
    if (g.below(2)) runs.push_back({g.phrase(4), &third});
    for (int kind = 0; kind < 2; ++kind) {
      const plot::PlotSpec spec =
          kind == 0 ? plot::default_comparison_spec(runs)
                    : plot::comparison_spec(
                          runs, {scene.columns[1].name, scene.columns.back().name}, scene.columns);
      const plot::Figure figure = plot::make_comparison_figure(spec, runs);
      plot::FigureLayout layout;
      const image::Image img = plot::render(figure, &layout);
      const std::string name = stem + "_compare_" + std::to_string(kind);
      save(img, name);
      check(figure, layout, name, tally);
    }

    // study's work-precision plot: a long scene name, integrators with long names.
    {
      services::StudyResult study;
      study.scene = g.name(2 + g.below(4));
      study.reference_dt = 1e-5;
      study.event_names = {g.word() + " stick"};
      const int integrators = 2 + g.below(5);
      for (int i = 0; i < integrators; ++i) {
        const std::string integrator = g.name(1 + g.below(3));
        for (int k = 0; k < 5; ++k) {
          services::StudyRow row;
          row.integrator = integrator;
          row.status = "ok";
          row.wall_seconds = std::pow(10.0, -3.0 + 0.5 * k + 0.2 * i);
          row.key_error = std::pow(10.0, -2.0 - (1.0 + i) * 0.6 * k);
          row.max_event_relative_error = std::pow(10.0, -1.0 - 0.5 * k - 0.1 * i);
          study.rows.push_back(row);
        }
      }
      const plot::Figure figure = services::work_precision_plot(study);
      plot::FigureLayout layout;
      const image::Image img = plot::render(figure, &layout);
      save(img, stem + "_study");
      check(figure, layout, stem + "_study", tally);
    }

    // The video's inset: long labels on a 360p and a 720p frame.
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) {
      render::InsetSettings settings;
      for (std::size_t c = 1; c < scene.columns.size() && settings.signals.size() < 2; c += 2) {
        settings.signals.push_back(scene.columns[c].name);
        settings.labels.push_back(g.phrase(4));
        settings.units.push_back(g.unit());
      }
      settings.width = g.uniform(0.3, 0.5);
      settings.height = g.uniform(0.3, 0.5);
      std::vector<render::InsetEvent> inset_events;
      for (const plot::PlotEvent& e : events) inset_events.push_back({e.time, e.kind});
      render::InsetPlot inset(settings, run, w, h, inset_events);
      const plot::FigureLayout& layout = inset.drawn_layout(0.5 * duration);
      // The inset's figure as it builds it: its labels, units and event kinds are the words.
      plot::Figure given;
      given.x_label = "t";
      given.x_unit = "s";
      for (std::size_t i = 0; i < settings.signals.size(); ++i) {
        plot::Panel& p = given.panels.emplace_back();
        p.label = settings.labels[i];
        p.unit = settings.units[i];
      }
      for (const render::InsetEvent& e : inset_events) given.events.push_back({e.time, e.kind});
      check(given, layout, stem + "_inset_" + std::to_string(h) + "p", tally, false);
      image::Image frame(w, h, {40, 60, 80, 255});
      inset.draw(frame, 0.5 * duration);
      save(frame, stem + "_inset_" + std::to_string(h) + "p");
    }
  }
  // What the checks saw (a check over nothing would pass).
  INFO(tally.figures << " figures, " << tally.texts << " texts (" << tally.shortened
                     << " shortened), legends " << tally.legends_inside << " inside, "
                     << tally.legends_outside << " outside");
  CHECK(tally.figures > 100);
  CHECK(tally.legends_inside > 10);
  WARN(tally.figures << " figures, " << tally.texts << " texts (" << tally.shortened
                     << " shortened), legends " << tally.legends_inside << " inside, "
                     << tally.legends_outside << " outside");
}
