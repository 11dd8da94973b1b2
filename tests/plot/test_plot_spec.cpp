#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

#include "plot/plot_spec.hpp"
#include "scene/toml_reader.hpp"
#include "synthetic.hpp"

using namespace stiction;

namespace {

const std::vector<std::string> kColumns{"t", "sphere.p.z", "sphere.v.x", "ground.slip.x"};

std::vector<plot::PlotSpec> read(const std::string& text) {
  const toml::table doc = toml::parse(std::string_view(text), std::string_view("scenes/test.toml"));
  return plot::read_plot_specs(doc, "scenes/test.toml", kColumns);
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const scene::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("plot specs are read from [[plots]]", "[plot][spec]") {
  const auto specs = read(R"(
[simulation]
duration = 1.0

[[plots]]
name = "fig4"
title = "Sphere"
size = [1200, 800]
time = [0.0, 0.8]
events = ["ground.stick_time"]
  [[plots.panels]]
  signals = ["sphere.v.x", "ground.slip.x"]
  legend = ["centre", "contact point"]
  label = "Horizontal velocity"
  unit = "m/s"
  [[plots.panels]]
  signals = ["sphere.p.z"]
  log = true
  relative_to = 0.5

[[plots]]
  [[plots.panels]]
  signals = ["sphere.p.z"]
)");
  REQUIRE(specs.size() == 2);
  const plot::PlotSpec& a = specs[0];
  CHECK(a.name == "fig4");
  CHECK(a.title == "Sphere");
  CHECK(a.width == 1200);
  CHECK(a.height == 800);
  CHECK(a.t_min == 0.0);
  CHECK(a.t_max == 0.8);
  CHECK(a.only_events == std::vector<std::string>{"ground.stick_time"});
  REQUIRE(a.panels.size() == 2);
  CHECK(a.panels[0].signals == std::vector<std::string>{"sphere.v.x", "ground.slip.x"});
  CHECK(a.panels[0].legend[1] == "contact point");
  CHECK(a.panels[0].unit == "m/s");
  CHECK_FALSE(a.panels[0].log);
  CHECK(a.panels[1].log);
  CHECK(a.panels[1].relative_to == 0.5);
  CHECK(specs[1].name == "plot2");
  CHECK(specs[1].width == 1600);
  CHECK(specs[1].mark_events);
  CHECK(specs[1].labels.mode == plot::EventLabels::Mode::important);
  CHECK_FALSE(a.print);  // `size` in pixels: the legacy figure, text scaling with it
  REQUIRE(specs[1].print);
  CHECK(specs[1].print->width_mm == 88.0);
  CHECK(specs[1].print->font_pt == 8.0);
  CHECK(specs[1].dpi == 300.0);
  CHECK(read("[simulation]\nduration = 1.0\n").empty());
}

TEST_CASE("an unknown signal names file, line, column, the signal and the columns",
          "[plot][spec]") {
  const std::string message = error_of(R"([[plots]]
name = "p"
  [[plots.panels]]
  signals = ["sphere.v.x", "sphere.vel.x"]
)");
  CHECK_THAT(message, Catch::StartsWith("scenes/test.toml:4:28: error:"));
  CHECK_THAT(message, Catch::Contains("'sphere.vel.x'"));
  CHECK_THAT(message, Catch::Contains("sphere.p.z, sphere.v.x, ground.slip.x"));
  CHECK_THAT(message, Catch::Contains("plots[0].panels[0].signals"));
}

TEST_CASE("bad plot specs are input errors at their position", "[plot][spec]") {
  CHECK_THAT(
      error_of("[[plots]]\ncolour = 1\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"),
      Catch::StartsWith("scenes/test.toml:2:") && Catch::Contains("unknown key 'plots[0].colour'"));
  CHECK_THAT(
      error_of("[[plots]]\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n  colour = 1\n"),
      Catch::Contains("unknown key 'plots[0].panels[0].colour'"));
  CHECK_THAT(error_of("[[plots]]\nname = \"x\"\n"), Catch::Contains("panels"));
  CHECK_THAT(error_of("[[plots]]\n  [[plots.panels]]\n  label = \"v\"\n"),
             Catch::Contains("signals") && Catch::Contains("missing"));
  CHECK_THAT(error_of("[[plots]]\n  [[plots.panels]]\n  signals = []\n"),
             Catch::Contains("at least one signal"));
  CHECK_THAT(error_of("[[plots]]\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"
                      "  legend = [\"a\", \"b\"]\n"),
             Catch::StartsWith("scenes/test.toml:4:") && Catch::Contains("one entry per signal"));
  CHECK_THAT(
      error_of("[[plots]]\nsize = [100, 100]\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"),
      Catch::StartsWith("scenes/test.toml:2:") && Catch::Contains("size"));
  CHECK_THAT(
      error_of("[[plots]]\nname = \"../x\"\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"),
      Catch::Contains("file name"));
  CHECK_THAT(
      error_of("[[plots]]\ntime = [1, 0]\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"),
      Catch::Contains("end > start"));
  CHECK_THAT(
      error_of("[[plots]]\nname = \"a\"\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"
               "[[plots]]\nname = \"a\"\n  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n"),
      Catch::StartsWith("scenes/test.toml:6:") && Catch::Contains("exists already"));
  CHECK_THAT(error_of("plots = 3\n"), Catch::Contains("array of tables"));
}

TEST_CASE("the paper figures come first among the defaults, then every signal", "[plot][spec]") {
  auto all_signals = [](const std::vector<plot::PlotSpec>& specs) {
    std::set<std::string> drawn;
    for (const plot::PlotSpec& spec : specs) {
      for (const plot::PanelSpec& p : spec.panels) drawn.insert(p.signals.begin(), p.signals.end());
    }
    return drawn;
  };
  const core::Trajectory sphere_run = plot::testing::sphere_run(0.1);
  const auto sphere = plot::default_plot_specs(sphere_run.columns());
  REQUIRE(sphere.size() == 3);  // Fig. 4, then five signal groups in two figures
  CHECK(sphere[0].name == plot::paper_fig4_spec().name);
  CHECK(sphere[1].name == "signals_1");
  CHECK(sphere[2].name == "signals_2");
  CHECK(sphere[1].panels.size() + sphere[2].panels.size() == 5);
  CHECK(all_signals(sphere).size() == sphere_run.columns().size() - 1);
  const auto arm = plot::default_plot_specs(plot::testing::arm_run(0.1).columns());
  REQUIRE(arm.size() >= 2);
  CHECK(arm[0].name == plot::paper_fig7_spec().name);
  const auto other = plot::default_plot_specs({"t", "box.p.x", "box.p.y", "box.v.x", "spring.f"});
  REQUIRE(other.size() == 1);
  CHECK(other[0].name == "signals");
  REQUIRE(other[0].panels.size() == 3);
  CHECK(other[0].panels[0].signals == std::vector<std::string>{"box.p.x", "box.p.y"});
  CHECK(other[0].panels[0].legend == std::vector<std::string>{"x", "y"});
  CHECK(other[0].panels[0].unit == "m");
  CHECK(other[0].panels[1].unit == "m/s");
  CHECK(other[0].panels[2].signals == std::vector<std::string>{"spring.f"});
  CHECK(other[0].panels[2].unit == "N");
  CHECK(plot::default_plot_specs({"t"}).empty());
  // Many groups: no cap, several figures of at most kPanelsPerFigure panels.
  std::vector<std::string> many{"t"};
  for (int i = 0; i < 23; ++i) {
    std::string name = std::to_string(i);
    name.insert(0, 1, 'c');
    name += ".f";
    many.push_back(name);
  }
  std::vector<std::string> not_drawn;
  const auto specs = plot::default_plot_specs(many, &not_drawn);
  CHECK(specs.size() == 6);
  for (const auto& spec : specs) CHECK(spec.panels.size() <= plot::kPanelsPerFigure);
  CHECK(all_signals(specs).size() == 23);
  CHECK(not_drawn.empty());
  // Beyond the cap (issue 39: 20 spheres pairwise drew 210 figures): kMaxDefaultFigures
  // figures, the first groups in column order drawn, every other one named, none lost.
  const int cap = plot::kMaxDefaultFigures * plot::kPanelsPerFigure;
  // Names built by append: GCC 12's -Wrestrict misfires on "c" + std::to_string(i).
  auto group = [](int i) { return std::string(1, 'c').append(std::to_string(i)).append(".f"); };
  for (int i = 23; i < cap + 37; ++i) many.push_back(group(i));
  const auto capped = plot::default_plot_specs(many, &not_drawn);
  CHECK(capped.size() == static_cast<std::size_t>(plot::kMaxDefaultFigures));
  CHECK(all_signals(capped).size() == static_cast<std::size_t>(cap));
  CHECK(all_signals(capped).count("c0.f") == 1);
  REQUIRE(not_drawn.size() == 37);
  CHECK(not_drawn.front() == group(cap));
  CHECK(not_drawn.back() == group(cap + 36));
}

TEST_CASE("figures from a run: series, events and relative signals", "[plot][spec]") {
  const core::Trajectory run = plot::testing::sphere_run(1.0);
  const std::map<std::string, double> events{{"ground.stick_time", 0.6033},
                                             {"ground.slip_time", 0.01}};
  plot::PlotSpec spec = plot::paper_fig4_spec();
  plot::Figure figure = plot::make_figure(spec, run, events);
  REQUIRE(figure.panels.size() == 2);
  CHECK(figure.panels[0].series.size() == 2);
  CHECK(figure.panels[0].series[0].x.size() == static_cast<std::size_t>(run.row_count()));
  REQUIRE(figure.events.size() == 2);
  CHECK(figure.events[0].label == "slip 0.01 s");
  CHECK(figure.events[0].labelled);  // the break-away from the start
  CHECK(figure.events[1].label == "stick 0.6033 s");
  CHECK(figure.events[1].labelled);
  spec.only_events = {"ground.stick_time"};
  CHECK(plot::make_figure(spec, run, events).events.size() == 1);
  spec.mark_events = false;
  CHECK(plot::make_figure(spec, run, events).events.empty());

  spec.t_min = 0.2;
  spec.t_max = 0.4;
  spec.panels[1].relative_to = 0.5;  // after the window: no samples, no NaN
  figure = plot::make_figure(spec, run, std::vector<plot::PlotEvent>{});
  const auto& x = figure.panels[0].series[0].x;
  CHECK(x.front() >= 0.199 - 1e-9);
  CHECK(x.back() <= 0.401 + 1e-9);
  CHECK(figure.panels[1].series[0].x.empty());

  plot::PlotSpec rel;
  plot::PanelSpec v;
  v.signals = {"sphere.v.x"};
  v.relative_to = 0.25;
  rel.panels.push_back(v);
  figure = plot::make_figure(rel, run, std::vector<plot::PlotEvent>{});
  const plot::Series& s = figure.panels[0].series[0];
  CHECK(s.x.front() == Approx(0.25));
  CHECK(s.y.front() == Approx(0.0).margin(1e-12));
  CHECK(s.y.back() < 0.0);

  plot::PlotSpec bad = plot::paper_fig7_spec();
  CHECK_THROWS_WITH(plot::make_figure(bad, run, std::vector<plot::PlotEvent>{}),
                    Catch::Contains("arm.theta.0") && Catch::Contains("sphere.v.x"));
}

TEST_CASE("comparison figures label runs by name and need the signals in every run",
          "[plot][spec]") {
  const core::Trajectory a = plot::testing::arm_run(6.0);
  const core::Trajectory b = plot::testing::arm_run(6.0, 0.01);
  const std::vector<plot::Run> runs{{"two_link", &a}, {"two_link_lugre", &b}};
  const plot::PlotSpec spec = plot::default_comparison_spec(runs);
  CHECK(spec.name == plot::drift_comparison_spec().name);
  const plot::Figure figure = plot::make_comparison_figure(spec, runs);
  CHECK(figure.title == "two_link vs two_link_lugre");
  REQUIRE(figure.panels.size() == 3);
  REQUIRE(figure.panels[0].series.size() == 2);
  CHECK(figure.panels[0].series[0].label == "two_link");
  CHECK(figure.panels[0].series[1].label == "two_link_lugre");
  REQUIRE(figure.panels[2].series.size() == 4);
  CHECK(figure.panels[2].series[1].label == "two_link_lugre: \u03B8\u2080");
  // One colour per run in every panel, one dash pattern per series within a panel.
  CHECK(figure.panels[2].series[0].style->colour == figure.panels[0].series[0].style->colour);
  CHECK(figure.panels[2].series[0].style->dash != figure.panels[2].series[2].style->dash);
  // Drift panel: Kikuuwe-like run flat at zero, drifting run growing.
  CHECK(std::abs(figure.panels[2].series[0].y.back()) < 1e-12);
  CHECK(figure.panels[2].series[1].y.back() == Approx(0.01).epsilon(0.05));

  const core::Trajectory sphere = plot::testing::sphere_run(0.1);
  CHECK_THROWS_WITH(
      plot::make_comparison_figure(spec, {{"two_link", &a}, {"sphere_roll", &sphere}}),
      Catch::StartsWith("run 'sphere_roll'"));
}

TEST_CASE("a plot's format comes from its name's extension or `format`, dpi from `dpi`",
          "[plot][spec]") {
  const std::string panel = "  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n";
  auto with = [&](const std::string& keys) {
    std::string text = "[[plots]]\n";
    text += keys;
    text += panel;
    return text;
  };
  auto one = [&](const std::string& keys) { return read(with(keys)).at(0); };
  const plot::PlotSpec svg = one("name = \"block.svg\"\n");
  CHECK(svg.name == "block");
  CHECK(svg.format == plot::Format::svg);
  CHECK(plot::plot_path(svg, "plots") == std::filesystem::path("plots/block.svg"));
  CHECK(plot::plot_path(svg, "plots", plot::Format::pdf) ==
        std::filesystem::path("plots/block.pdf"));
  const plot::PlotSpec pdf = one("name = \"b\"\nformat = \"PDF\"\ndpi = 300\n");
  CHECK(pdf.format == plot::Format::pdf);
  CHECK(pdf.dpi == 300.0);
  const plot::PlotSpec plain = one("name = \"fig.v2\"\n");
  CHECK(plain.name == "fig.v2");
  CHECK(!plain.format);
  CHECK(plot::plot_path(plain, "p") == std::filesystem::path("p/fig.v2.png"));
  CHECK_THAT(error_of(with("name = \"a.svg\"\nformat = \"pdf\"\n")),
             Catch::StartsWith("scenes/test.toml:3:") && Catch::Contains("contradicts"));
  CHECK_THAT(error_of(with("format = \"jpeg\"\n")), Catch::Contains("\"svg\""));
  CHECK_THAT(error_of(with("dpi = 5\n")), Catch::Contains("dpi"));
}

TEST_CASE("a panel without label or unit takes them from the columns it shows", "[plot][spec]") {
  // Generated names of every length: the label is the signal name for one signal, the names
  // for a short list, nothing for a long one (the legend names them); the unit is the one the
  // components declare when the signals share it, none when they differ.
  for (const std::size_t length : {1u, 8u, 30u}) {
    const std::string a(length, 'a');
    const std::string b(length, 'b');
    const std::vector<core::ColumnInfo> columns{{"t", "s", "", ""},
                                                {a + ".f.x", "N", "world", "force"},
                                                {b + ".tau", "N·m", "", "torque"},
                                                {b + ".f.x", "N", "world", "force"},
                                                {b + ".q.w", "", "", "quaternion"}};
    const std::string text = "[[plots]]\n  [[plots.panels]]\n  signals = [\"" + a +
                             ".f.x\"]\n  [[plots.panels]]\n  signals = [\"" + a + ".f.x\", \"" + b +
                             ".f.x\"]\n  [[plots.panels]]\n  signals = [\"" + a + ".f.x\", \"" + b +
                             ".tau\"]\n  label = \"Mixed\"\n" +
                             "  [[plots.panels]]\n  signals = [\"" + b +
                             ".q.w\"]\n  unit = \"-\"\n";
    const toml::table doc = toml::parse(std::string_view(text), std::string_view("gen.toml"));
    const auto specs = plot::read_plot_specs(doc, "gen.toml", columns);
    REQUIRE(specs.size() == 1);
    const auto& p = specs[0].panels;
    REQUIRE(p.size() == 4);
    CHECK(p[0].label == a + ".f.x");
    CHECK(p[0].unit == "N");
    const std::string both = a + ".f.x, " + b + ".f.x";
    CHECK(p[1].label == (both.size() <= 40 ? both : std::string()));
    CHECK(p[1].unit == "N");
    CHECK(p[2].label == "Mixed");  // given: kept
    CHECK(p[2].unit.empty());      // N and N·m: no common unit
    CHECK(p[3].label == b + ".q.w");
    CHECK(p[3].unit == "-");  // given: kept
  }
}

TEST_CASE("print size keys: width, height, font_size, dpi fill Figure::print", "[plot][spec]") {
  const std::string panel = "  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n";
  auto with = [&](const std::string& keys, int panels = 1) {
    std::string text = "[[plots]]\n" + keys;
    for (int i = 0; i < panels; ++i) text += panel;
    return text;
  };
  const core::Trajectory run = plot::testing::sphere_run(0.1);
  // Defaults: a one-column figure, 88 mm wide, 8 pt text, 300 dpi, its height by panel count.
  for (int panels = 1; panels <= 5; ++panels) {
    const plot::PlotSpec spec = read(with("", panels)).at(0);
    const plot::Figure figure = plot::make_figure(spec, run, std::vector<plot::PlotEvent>{});
    REQUIRE(figure.print);
    CHECK(figure.print->width_mm == 88.0);
    CHECK(figure.print->height_mm == plot::default_height_mm(static_cast<std::size_t>(panels)));
    CHECK(figure.print->font_pt == 8.0);
    CHECK(figure.print->dpi == 300.0);
  }
  CHECK(plot::default_height_mm(1) == 54.0);
  CHECK(plot::default_height_mm(2) == 80.0);
  CHECK(plot::default_height_mm(100) == 230.0);
  // Units: mm, cm, in, or a bare number of mm; font size in pt.
  const struct {
    std::string keys;
    double width, height, font;
  } cases[] = {{"width = \"3.5 in\"\nheight = \"7 cm\"\n", 88.9, 70.0, 8.0},
               {"width = 120\nfont_size = 9.5\n", 120.0, 54.0, 9.5},
               {"width = \"180mm\"\nheight = 100.5\nfont_size = \"10 pt\"\n", 180.0, 100.5, 10.0}};
  for (const auto& c : cases) {
    INFO(c.keys);
    const plot::Figure figure =
        plot::make_figure(read(with(c.keys)).at(0), run, std::vector<plot::PlotEvent>{});
    REQUIRE(figure.print);
    CHECK(figure.print->width_mm == Approx(c.width));
    CHECK(figure.print->height_mm == Approx(c.height));
    CHECK(figure.print->font_pt == c.font);
  }
  const plot::PlotSpec dpi = read(with("dpi = 600\n")).at(0);
  CHECK(plot::make_figure(dpi, run, std::vector<plot::PlotEvent>{}).print->dpi == 600.0);
  // The legacy pixel size: no print size.
  CHECK_FALSE(plot::make_figure(read(with("size = [800, 600]\n")).at(0), run,
                                std::vector<plot::PlotEvent>{})
                  .print.has_value());
  // Errors at the key: bad units, ranges, both kinds of size, too many pixels.
  CHECK_THAT(error_of(with("width = \"88 px\"\n")), Catch::StartsWith("scenes/test.toml:2:9:") &&
                                                        Catch::Contains("plots[0].width") &&
                                                        Catch::Contains("mm, cm or in"));
  CHECK_THAT(error_of(with("height = \"tall\"\n")),
             Catch::StartsWith("scenes/test.toml:2:") && Catch::Contains("plots[0].height"));
  CHECK_THAT(error_of(with("width = 5\n")), Catch::Contains("20 mm .. 1000 mm"));
  CHECK_THAT(error_of(with("width = \"2 in\"\nheight = \"1 in\"\n")), Catch::Contains("no error"));
  CHECK_THAT(error_of(with("font_size = 2\n")),
             Catch::Contains("plots[0].font_size") && Catch::Contains("4 .. 72 pt"));
  CHECK_THAT(error_of(with("font_size = \"8 px\"\n")), Catch::Contains("points"));
  CHECK_THAT(error_of(with("width = true\n")), Catch::Contains("plots[0].width"));
  CHECK_THAT(error_of(with("size = [800, 600]\nwidth = 88\n")),
             Catch::StartsWith("scenes/test.toml:2:") && Catch::Contains("plots[0].size") &&
                 Catch::Contains("excludes width"));
  CHECK_THAT(error_of(with("size = [800, 600]\nfont_size = 8\n")),
             Catch::Contains("excludes font_size"));
  CHECK_THAT(error_of(with("width = \"30 cm\"\ndpi = 2000\n")),
             Catch::StartsWith("scenes/test.toml:3:") && Catch::Contains("plots[0].dpi") &&
                 Catch::Contains("pixels"));
}

TEST_CASE("`labels` and `events` take event selectors, checked against the run's components",
          "[plot][spec]") {
  const std::string panel = "  [[plots.panels]]\n  signals = [\"sphere.p.z\"]\n";
  auto with = [&](const std::string& keys) { return "[[plots]]\n" + keys + panel; };
  using Mode = plot::EventLabels::Mode;
  CHECK(read(with("labels = \"all\"\n")).at(0).labels.mode == Mode::all);
  CHECK(read(with("labels = \"none\"\n")).at(0).labels.mode == Mode::none);
  CHECK(read(with("labels = \"important\"\n")).at(0).labels.mode == Mode::important);
  const plot::PlotSpec listed =
      read(with("labels = [\"ground.first_stick\", \"sphere\", \"ground.final_stop\"]\n")).at(0);
  CHECK(listed.labels.mode == Mode::listed);
  CHECK(listed.labels.selectors.size() == 3);
  CHECK(read(with("events = [\"ground.touch_down\", \"ground.slip_time\"]\n"))
            .at(0)
            .only_events.size() == 2);
  CHECK_THAT(error_of(with("labels = \"some\"\n")), Catch::StartsWith("scenes/test.toml:2:") &&
                                                        Catch::Contains("plots[0].labels") &&
                                                        Catch::Contains("\"important\""));
  CHECK_THAT(error_of(with("labels = 3\n")), Catch::Contains("plots[0].labels"));
  CHECK_THAT(error_of(with("labels = [\"ground.stop\"]\n")),
             Catch::StartsWith("scenes/test.toml:2:11:") && Catch::Contains("plots[0].labels[0]") &&
                 Catch::Contains("unknown event 'stop'"));
  CHECK_THAT(error_of(with("events = [\"ground\", \"floor.stick\"]\n")),
             Catch::StartsWith("scenes/test.toml:2:21:") && Catch::Contains("plots[0].events[1]") &&
                 Catch::Contains("'floor' is not a component") &&
                 Catch::Contains("sphere, ground"));
  // A contact of several points names each point's events by NAME.i (box_slope's
  // "floor.0.stick_time"); a point that does not exist, or a signal, is not an element.
  const std::vector<std::string> box_columns{"t", "box.p.z", "floor.0.slip.x", "floor.1.slip.x"};
  const std::string box_panel = "  [[plots.panels]]\n  signals = [\"box.p.z\"]\n";
  const auto read_box = [&](const std::string& keys) {
    const std::string text = "[[plots]]\n" + keys + box_panel;
    const toml::table doc = toml::parse(std::string_view(text), std::string_view("box.toml"));
    return plot::read_plot_specs(doc, "box.toml", box_columns);
  };
  CHECK(read_box("events = [\"floor.0.stick_time\", \"floor.1\", \"floor\"]\n")
            .at(0)
            .only_events.size() == 3);
  for (const std::string bad : {"floor.2", "box.0", "floor.0.1"}) {
    INFO(bad);
    CHECK_THROWS_WITH(read_box("events = [\"" + bad + "\"]\n"),
                      Catch::Contains("is not a component of the run"));
  }
}

TEST_CASE("default figures leave out signals that are zero throughout, and say so",
          "[plot][spec]") {
  // Generated runs: a body moving in a random subset of its axes; its velocity panel draws
  // the moving axes and names the others in the caption.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    const int moving = std::uniform_int_distribution<int>(0, 7)(rng);  // bit per axis
    core::Trajectory run({"t", "b.v.x", "b.v.y", "b.v.z"});
    for (int i = 0; i < 50; ++i) {
      const double t = 0.01 * i;
      const double row[] = {t, (moving & 1) ? std::sin(t + 1) : 0.0,
                            (moving & 2) ? 1e-300 * t : 0.0, (moving & 4) ? -t : 0.0};
      run.append(row);
    }
    const auto specs = plot::default_plot_specs(run.columns());
    REQUIRE(specs.size() == 1);
    const plot::Figure figure = plot::make_figure(specs[0], run, std::vector<plot::PlotEvent>{});
    REQUIRE(figure.panels.size() == 1);
    std::set<std::string> drawn;
    for (const plot::Series& s : figure.panels[0].series) drawn.insert(s.source);
    INFO("moving axes " << moving << ", caption " << figure.panels[0].caption);
    std::string omitted;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string name = std::string("b.v.") + "xyz"[axis];
      const bool moves = moving & (1 << axis);
      CHECK(drawn.count(name) == (moves || moving == 0 ? 1u : 0u));
      if (!moves && moving != 0) omitted += std::string("v.") + "xyz"[axis] + " = ";
    }
    if (omitted.empty()) {
      CHECK(figure.panels[0].caption.find("not drawn") == std::string::npos);
    } else {
      CHECK_THAT(figure.panels[0].caption, Catch::EndsWith("(" + omitted + "0, not drawn)"));
    }
  }
  // A user's panel draws what it names, zero or not.
  const core::Trajectory sphere = plot::testing::sphere_run(0.1);
  plot::PlotSpec spec;
  plot::PanelSpec p;
  p.signals = {"sphere.v.x", "sphere.p.x"};
  spec.panels.push_back(p);
  core::Trajectory zero({"t", "sphere.v.x", "sphere.p.x"});
  for (int i = 0; i < 3; ++i) {
    const double row[] = {0.1 * i, 0.0, 0.1 * i};
    zero.append(row);
  }
  CHECK(plot::make_figure(spec, zero, std::vector<plot::PlotEvent>{}).panels[0].series.size() == 2);
}

TEST_CASE("a comparison of one axis is titled by that signal, not its group", "[plot][spec]") {
  // `stiction compare --signals ball.v.x`: the panel says "ball.v.x", its y label "v.x".
  core::Trajectory a({"t", "ball.v.x", "ball.v.y", "ball.v.z"});
  for (int i = 0; i < 20; ++i) {
    const double t = 0.05 * i;
    const double row[] = {t, 1.0 - t, 0.0, 0.5 * t};
    a.append(row);
  }
  const core::Trajectory b = a;
  const std::vector<plot::Run> runs{{"a", &a}, {"b", &b}};
  const std::vector<core::ColumnInfo> columns{
      {"ball.v.x", "m/s", "world", "velocity of the centre, component x"},
      {"ball.v.y", "m/s", "world", "velocity of the centre, component y"},
      {"ball.v.z", "m/s", "world", "velocity of the centre, component z"}};
  plot::PlotSpec spec = plot::comparison_spec(runs, {"ball.v.x"}, columns);
  REQUIRE(spec.panels.size() == 1);
  CHECK(spec.panels[0].caption == "ball.v.x: velocity of the centre");
  CHECK(spec.panels[0].label == "v.x");
  CHECK(spec.panels[0].unit == "m/s");
  // The whole group: titled by the group; y, zero in both runs, is left out and named.
  spec = plot::comparison_spec(runs, {"ball.v"}, columns);
  REQUIRE(spec.panels.size() == 1);
  const plot::Figure figure = plot::make_comparison_figure(spec, runs);
  CHECK(figure.panels[0].label == "v");
  CHECK(figure.panels[0].caption == "ball.v: velocity of the centre (v.y = 0, not drawn)");
  CHECK(figure.panels[0].series.size() == 4);  // x and z of both runs
  // Only x moving: the one axis left names itself.
  core::Trajectory c({"t", "ball.v.x", "ball.v.y", "ball.v.z"});
  for (int i = 0; i < 20; ++i) {
    const double row[] = {0.05 * i, 1.0, 0.0, 0.0};
    c.append(row);
  }
  const std::vector<plot::Run> flat{{"a", &c}, {"c", &c}};
  const plot::Figure one =
      plot::make_comparison_figure(plot::comparison_spec(flat, {"ball.v"}, columns), flat);
  CHECK(one.panels[0].label == "v.x");
  CHECK(one.panels[0].caption == "ball.v: velocity of the centre (v.y = v.z = 0, not drawn)");
}

TEST_CASE("compare without --signals draws the signals that differ most", "[plot][compare]") {
  // Two runs over 0..2 s (the second sampled at other times): ball.v.x differs by half its
  // range, ball.p.x by a quarter, ball.v.z by 1%, ball.p.z and ground.f.z not at all.
  auto run = [](double dt, double gap) {
    core::Trajectory t({"t", "ball.p.x", "ball.p.z", "ball.v.x", "ball.v.z", "ground.f.z"});
    for (double time = 0.0; time <= 2.0 + 1e-12; time += dt) {
      const double row[] = {time,
                            time + 0.25 * gap * time,
                            0.1,
                            std::sin(time) + 0.5 * gap * time,
                            std::cos(3 * time) * (1.0 + 0.01 * gap),
                            2.9};
      t.append(row);
    }
    return t;
  };
  const core::Trajectory a = run(1e-3, 0.0), b = run(1.3e-3, 1.0);
  const std::vector<plot::Run> runs{{"a", &a}, {"b", &b}};
  const plot::PlotSpec spec = plot::default_comparison_spec(runs);
  std::vector<std::string> drawn;
  for (const plot::PanelSpec& p : spec.panels) {
    drawn.insert(drawn.end(), p.signals.begin(), p.signals.end());
  }
  CHECK(spec.name == "compare");
  CHECK(drawn == std::vector<std::string>{"ball.p.x", "ball.v.x"});
  // Runs that agree everywhere: the first default figure of what they share.
  const std::vector<plot::Run> same{{"a", &a}, {"a again", &a}};
  const plot::PlotSpec fallback = plot::default_comparison_spec(same);
  CHECK(!fallback.panels.empty());
  // At most kCompareSignals signals, each in a panel of its own, however many differ.
  core::Trajectory many({"t", "s0.x", "s1.x", "s2.x", "s3.x", "s4.x", "s5.x"});
  core::Trajectory others(many.columns());
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i;
    const double r1[] = {t, t, 2 * t, 3 * t, 4 * t, 5 * t, 6 * t};
    const double r2[] = {t, -t, -2 * t, -3 * t, -4 * t, -5 * t, -6 * t};
    many.append(r1);
    others.append(r2);
  }
  const plot::PlotSpec capped = plot::default_comparison_spec({{"a", &many}, {"b", &others}});
  std::size_t signals = 0;
  for (const plot::PanelSpec& p : capped.panels) signals += p.signals.size();
  CHECK(signals <= plot::kCompareSignals);
  CHECK(capped.panels.size() <= plot::kComparePanels);
  CHECK(signals >= 3);
}

TEST_CASE("compare without --signals: a panel per signal, the runs' names once as its legend",
          "[plot][compare]") {
  // Two runs of a contact: both axes of its force and its normal force differ (as
  // roll_to_slip against sphere_roll), with long run names.
  auto run = [](double gain) {
    core::Trajectory t({"t", "ground.f.x", "ground.f.z", "ground.n_force", "ball.p.x"});
    for (int i = 0; i <= 2000; ++i) {
      const double time = 1e-3 * i;
      const double row[] = {time, gain * std::sin(9 * time), 300 * gain * (i % 97 == 0),
                            200 * gain * std::abs(std::cos(5 * time)), time};
      t.append(row);
    }
    return t;
  };
  const core::Trajectory a = run(0.05), b = run(1.0);
  const std::vector<plot::Run> runs{{"roll_to_slip_hollow", &a}, {"sphere_roll_long_name", &b}};
  const plot::PlotSpec spec = plot::default_comparison_spec(runs);
  REQUIRE(spec.panels.size() == 3);
  for (const plot::PanelSpec& p : spec.panels) CHECK(p.signals.size() == 1);
  const plot::Figure figure = plot::make_comparison_figure(spec, runs);
  std::vector<std::string> labels;
  int panels_with_labels = 0;
  for (const plot::Panel& p : figure.panels) {
    bool any = false;
    for (const plot::Series& s : p.series) {
      if (s.label.empty()) continue;
      labels.push_back(s.label);
      any = true;
    }
    panels_with_labels += any ? 1 : 0;
  }
  CHECK(panels_with_labels == 1);
  CHECK(labels == std::vector<std::string>{"roll_to_slip_hollow", "sphere_roll_long_name"});
  // On an 88 x 70 mm page the legend takes little of it and the panels most.
  plot::Figure page = figure;
  page.print = plot::Figure::Print{88.0, 70.0, 8.0, 300.0};
  const plot::FigureLayout layout = plot::write_figure(
      page, std::filesystem::path(STICTION_TEST_OUTPUT_DIR) / "compare_88x70.png",
      plot::Format::png);
  double legend_area = 0.0, data_area = 0.0;
  for (const plot::Rect& r : layout.legends) legend_area += r.width() * r.height();
  for (const plot::Rect& r : layout.panels) data_area += r.width() * r.height();
  const double page_area = static_cast<double>(layout.width) * layout.height;
  INFO("legends " << legend_area / page_area << ", panels " << data_area / page_area);
  CHECK(legend_area <= 0.06 * page_area);
  CHECK(data_area >= 0.2 * page_area);
  CHECK(plot::layout_problems(layout).empty());
}
