// No text is cut mid-word in any figure the program draws (issue 37 item 4): every figure of
// every bundled scene as `run` writes it (and `verify` compares it: the same figure), on its
// own page and on an 88 x 70 mm page, the default `compare` figure of runs of bundled scenes,
// a `study` work-precision figure and the video's inset of the scenes that have one. The
// figure's text layer records every string drawn with the text it was given
// (plot::TextBox::given) and whether the text rule shortened it; the check here is apart
// from the rule: the words of every string drawn must be whole words of what it was given,
// in order, and a string not marked shortened must be a run of consecutive words of it (a
// line of a wrapped text). "Ve…ity" for "Velocity" fails; "Key-signal error" for
// "Key-signal error (relative)", marked shortened, passes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/column_info.hpp"
#include "core/simulation.hpp"
#include "plot/plot_spec.hpp"
#include "render/inset_plot.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"
#include "services/plot_outputs.hpp"
#include "services/run_outputs.hpp"
#include "services/study.hpp"
#include "word_runs.hpp"

using namespace stiction;

using stiction::testing::word_runs;

namespace {

// What is wrong with one drawn string against what it was given ("" when nothing is): a word
// that is not a whole word of the given text, words out of order, or words left out of a
// string not marked shortened (it must then be consecutive words of it: a line of a wrapped
// text, or all of it).
std::string cut(const plot::TextBox& t) {
  const std::vector<std::string> drawn = word_runs(t.text), given = word_runs(t.given);
  // Every word a whole word of the given text, in order (a subsequence).
  std::size_t at = 0;
  for (const std::string& w : drawn) {
    const auto it = std::find(given.begin() + static_cast<long>(at), given.end(), w);
    if (it == given.end()) {
      return "'" + w + "' is not a whole word of '" + t.given + "' in its order";
    }
    at = static_cast<std::size_t>(it - given.begin()) + 1;
  }
  if (t.shortened || drawn.empty()) return "";
  // Not shortened: consecutive words of the given text.
  for (std::size_t start = 0; start + drawn.size() <= given.size(); ++start) {
    if (std::equal(drawn.begin(), drawn.end(), given.begin() + static_cast<long>(start))) {
      return "";
    }
  }
  return "words left out without being marked shortened (given '" + t.given + "')";
}

struct Tally {
  int figures = 0, texts = 0, shortened = 0;
  std::vector<std::string> problems;
};

void check(const plot::FigureLayout& layout, const std::string& name, Tally& tally) {
  ++tally.figures;
  for (const plot::TextBox& t : layout.texts) {
    ++tally.texts;
    if (t.shortened) ++tally.shortened;
    const std::string problem = cut(t);
    if (!problem.empty()) tally.problems.push_back(name + ": '" + t.text + "': " + problem);
  }
}

void check(const plot::Figure& figure, const std::string& name, Tally& tally) {
  plot::FigureLayout layout;
  plot::render(figure, &layout);
  check(layout, name, tally);
}

plot::Figure on_88_by_70(plot::Figure figure) {
  figure.print = plot::Figure::Print{88.0, 70.0, 8.0, 300.0};
  return figure;
}

plot::TextBox drawn(const std::string& text, const std::string& given, bool shortened) {
  plot::TextBox t;
  t.text = text;
  t.given = given;
  t.shortened = shortened;
  return t;
}

}  // namespace

TEST_CASE("the check finds a word cut in the middle", "[text-whole]") {
  // The cuts the issue reported, as the earlier shortening in the middle drew them.
  CHECK(!cut(drawn("Ve\u2026ity [m/s]", "Velocity [m/s]", true)).empty());
  CHECK(!cut(drawn("ce\u2026re speed", "centre speed", true)).empty());
  CHECK(!cut(drawn("fr\u2026ion", "friction", true)).empty());
  CHECK(
      !cut(drawn("Ke\u2026gnal error (re\u2026ive)", "Key-signal error (relative)", true)).empty());
  CHECK(!cut(drawn("Velo", "Velocity", false)).empty());
  // Words left out silently, and words out of order.
  CHECK(!cut(drawn("Key error", "Key-signal error", false)).empty());
  CHECK(!cut(drawn("error Key", "Key-signal error", true)).empty());
  // What the text rule does: whole words left out (marked), a wrapped line, a unit kept.
  CHECK(cut(drawn("Key-signal error", "Key-signal error (relative)", true)).empty());
  CHECK(cut(drawn("joint1_\u2026 stop 4.651 s", "joint1_friction stop 4.651 s", true)).empty());
  CHECK(cut(drawn("velocity of the", "Horizontal velocity of the sphere [m/s]", false)).empty());
  CHECK(cut(drawn("\u2026 sphere [m/s]", "Horizontal velocity of the sphere [m/s]", true)).empty());
  CHECK(cut(drawn("p(1 s)", "Drift p(t) \u2212 p(1 s) [m]", false)).empty());  // a wrapped line
}

TEST_CASE("no text is cut in any figure, inset or study plot of the bundled scenes",
          "[text-whole]") {
  Tally tally;
  std::vector<core::RunResult> results;
  std::vector<std::string> names;
  for (const auto& [name, description] : scene::bundled_scenes()) {
    scene::Scene scene = scene::load_scene(name);
    const std::vector<core::ColumnInfo> infos = core::column_infos(*scene.network);
    std::vector<plot::PlotSpec> specs =
        plot::read_plot_specs(scene.document, scene.path.string(), infos);
    if (specs.empty()) specs = plot::default_plot_specs(infos);
    const render::RenderSettings render = render::read_render_settings(scene);
    core::RunResult result = core::simulate(*scene.network, scene.run);
    REQUIRE(!result.instability);
    const core::Trajectory rows = services::plot_rows(result.trajectory);
    for (const plot::PlotSpec& spec : specs) {
      // run's figure, which verify compares too (services::run_figure).
      const plot::Figure figure = services::run_figure(spec, result, rows);
      check(figure, name + "/" + spec.name, tally);
      check(on_88_by_70(figure), name + "/" + spec.name + " at 88 x 70 mm", tally);
    }
    if (render.inset.enabled()) {
      std::vector<render::InsetEvent> events;
      for (const plot::PlotEvent& e : services::plot_events(result)) {
        events.push_back({e.time, e.kind});
      }
      for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) {
        render::InsetPlot inset(render.inset, result.trajectory, w, h, events);
        const double t_end = result.trajectory.at(result.trajectory.row_count() - 1, 0);
        check(inset.drawn_layout(0.5 * t_end),
              name + " inset " + std::to_string(w) + "x" + std::to_string(h), tally);
      }
    }
    results.push_back(std::move(result));
    names.push_back(name);
  }
  // compare without --signals: pairs of runs with signals in common.
  const std::vector<std::pair<std::string, std::string>> pairs{
      {"sphere_roll", "roll_to_slip"},
      {"roll_to_slip", "roll_to_slip_hollow"},
      {"two_link", "two_link_lugre"},
      {"box_push_tip", "box_push_slide"},
      {"slope_hold", "slope_slide"}};
  for (const auto& [a, b] : pairs) {
    const auto ia = std::find(names.begin(), names.end(), a);
    const auto ib = std::find(names.begin(), names.end(), b);
    REQUIRE(ia != names.end());
    REQUIRE(ib != names.end());
    const std::vector<plot::Run> runs{
        {a, &results[static_cast<std::size_t>(ia - names.begin())].trajectory},
        {b, &results[static_cast<std::size_t>(ib - names.begin())].trajectory}};
    const plot::Figure figure =
        plot::make_comparison_figure(plot::default_comparison_spec(runs), runs);
    check(figure, "compare " + a + " " + b, tally);
    check(on_88_by_70(figure), "compare " + a + " " + b + " at 88 x 70 mm", tally);
  }
  // study's work-precision figure: its own axis titles, every integrator, a scene name.
  services::StudyResult study;
  study.scene = "roll_to_slip_hollow";
  study.reference_dt = 1e-6;
  study.event_names = {"ground stick"};
  const std::vector<std::string> integrators{"euler",  "rk4",    "rk4_adaptive",
                                             "sdirk2", "sdirk4", "implicit"};
  for (std::size_t i = 0; i < integrators.size(); ++i) {
    for (int k = 0; k < 5; ++k) {
      services::StudyRow row;
      row.integrator = integrators[i];
      row.status = "ok";
      row.wall_seconds = std::pow(10.0, -3.0 + 0.5 * k + 0.2 * static_cast<double>(i));
      row.key_error = std::pow(10.0, -2.0 - (1.0 + static_cast<double>(i)) * 0.6 * k);
      row.max_event_relative_error = std::pow(10.0, -1.0 - 0.5 * k - 0.1 * static_cast<double>(i));
      study.rows.push_back(row);
    }
  }
  const plot::Figure study_figure = services::work_precision_plot(study);
  check(study_figure, "study", tally);
  check(on_88_by_70(study_figure), "study at 88 x 70 mm", tally);

  std::printf("text whole: %d figures, %d texts, %d shortened by whole words, %zu cut\n",
              tally.figures, tally.texts, tally.shortened, tally.problems.size());
  for (const std::string& p : tally.problems) UNSCOPED_INFO(p);
  CHECK(tally.problems.empty());
  CHECK(tally.figures > 60);
}
