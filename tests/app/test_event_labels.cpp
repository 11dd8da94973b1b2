// Which events the figures of real runs label (issue 21): the bundled sphere_roll and two_link
// scenes run through the services as `stiction run` runs them, their paper figures made from
// the run's events (services::plot_events). fig4 labels the first stick (the sphere starts to
// roll) and leaves its ~70 bounce touch-downs as ticks; fig7 labels each joint's final stop.
#include <algorithm>
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "plot/plot_spec.hpp"
#include "scene/scene.hpp"
#include "services/plot_outputs.hpp"
#include "services/run_service.hpp"

using namespace stiction;

namespace {

struct RealRun {
  services::PreparedRun prepared;
  services::RunOutcome outcome;
};

RealRun run_scene(const std::string& name) {
  services::RunRequest request;
  request.accuracy = false;
  RealRun run{services::prepare_run(scene::load_scene(name), request), {}};
  run.outcome = services::simulate_run(run.prepared, request);
  REQUIRE_FALSE(run.outcome.result.instability);
  return run;
}

const plot::PlotSpec& spec_named(const services::PreparedRun& run, const std::string& name) {
  for (const plot::PlotSpec& spec : run.plot_specs) {
    if (spec.name == name) return spec;
  }
  FAIL("no plot named " << name);
  throw;
}

std::vector<plot::EventMarker> labelled(const plot::Figure& figure) {
  std::vector<plot::EventMarker> out;
  for (const plot::EventMarker& e : figure.events) {
    if (e.labelled) out.push_back(e);
  }
  return out;
}

std::string describe(const std::vector<plot::EventMarker>& markers) {
  std::string text;
  for (const plot::EventMarker& e : markers) text += "\n  " + e.label;
  return text;
}

}  // namespace

TEST_CASE("sphere_roll's fig4 labels the first stick and leaves the bounces as ticks",
          "[plot][events]") {
  const RealRun run = run_scene("sphere_roll");
  const std::vector<plot::PlotEvent> events = services::plot_events(run.outcome.result);
  const plot::Figure figure = plot::make_figure(spec_named(run.prepared, "fig4_sphere"),
                                                run.outcome.result.trajectory, events);
  const auto& summary = run.outcome.summary["events"]["ground"];
  const double first_stick = summary["first_stick"].get<double>();
  const std::vector<plot::EventMarker> shown = labelled(figure);
  INFO(figure.events.size() << " markers, labelled:" << describe(shown));
  // Every stick and slip of the run is marked: the touch-downs as ticks.
  CHECK(figure.events.size() ==
        summary["events"].size() - static_cast<std::size_t>(std::count_if(
                                       summary["events"].begin(), summary["events"].end(),
                                       [](const auto& e) { return e["kind"] == "open"; })));
  CHECK(figure.events.size() > 40);
  // The contact never stays stuck (the sphere keeps hopping on its stiff contact), so the
  // first stick, where the contact point comes to rest and rolling starts, is the one label.
  REQUIRE(shown.size() == 1);
  CHECK(shown[0].x == first_stick);
  CHECK(first_stick == Approx(0.584).margin(0.001));
  CHECK(shown[0].kind == "stick");
  CHECK(shown[0].label == "stick 0.5843 s");
  // labels = "all" labels every marker; "none" none; a selector picks its events.
  plot::PlotSpec spec = spec_named(run.prepared, "fig4_sphere");
  spec.labels.mode = plot::EventLabels::Mode::all;
  const plot::Figure all = plot::make_figure(spec, run.outcome.result.trajectory, events);
  CHECK(labelled(all).size() == all.events.size());
  spec.labels.mode = plot::EventLabels::Mode::listed;
  spec.labels.selectors = {"ground.touch_down"};
  const plot::Figure touch_downs = plot::make_figure(spec, run.outcome.result.trajectory, events);
  const auto touch_down_count = std::count_if(
      summary["events"].begin(), summary["events"].end(),
      [](const auto& e) { return e.contains("touch_down") && e["touch_down"] == true; });
  CHECK(labelled(touch_downs).size() == static_cast<std::size_t>(touch_down_count));
  CHECK(labelled(touch_downs).front().label.rfind("touch-down ", 0) == 0);
}

TEST_CASE("two_link's fig7 labels each joint's final stop, with the joint's name",
          "[plot][events]") {
  const RealRun run = run_scene("two_link");
  const std::vector<plot::PlotEvent> events = services::plot_events(run.outcome.result);
  const plot::Figure figure = plot::make_figure(spec_named(run.prepared, "fig7_two_link"),
                                                run.outcome.result.trajectory, events);
  const std::vector<plot::EventMarker> shown = labelled(figure);
  INFO(figure.events.size() << " markers, labelled:" << describe(shown));
  for (const std::string joint : {"joint0_friction", "joint1_friction"}) {
    const auto& summary = run.outcome.summary["events"][joint];
    const double stop = summary["last_stick"].get<double>();
    const double first = summary["first_stick"].get<double>();
    CHECK(stop == Approx(4.6).margin(0.1));  // the arm comes to rest before the dither
    const auto at = [&](double t) {
      return std::find_if(shown.begin(), shown.end(), [&](const plot::EventMarker& e) {
        return e.x == t && e.label.rfind(joint + " ", 0) == 0;
      });
    };
    REQUIRE(at(stop) != shown.end());
    CHECK(at(stop)->label.find(" stop ") != std::string::npos);
    CHECK(at(first) == shown.end());
    // The stop is the last event: no event of the joint after it.
    CHECK(summary["events"].back()["time"].get<double>() == stop);
    // Labelled (the spec's list): the break-away from the start and the stop; the first stick,
    // the re-sticks and the slips ending them are ticks.
    const auto labelled_of = [&](const std::string& word) {
      return std::count_if(shown.begin(), shown.end(), [&](const plot::EventMarker& e) {
        return e.label.rfind(joint + " " + word + " ", 0) == 0;
      });
    };
    const auto& list = summary["events"];
    REQUIRE(list.size() >= 4);
    CHECK(list[0]["kind"] == "slip");
    CHECK(list[1]["kind"] == "stick");
    CHECK(list[1]["time"].get<double>() == first);
    CHECK(labelled_of("slip") == 1);
    CHECK(at(list[0]["time"].get<double>()) != shown.end());
    CHECK(labelled_of("stick") == 0);
    CHECK(labelled_of("stop") == 1);
  }
}

TEST_CASE("a pushed box's figures label its tip or its slide, and its corners' events are ticks",
          "[plot][events]") {
  for (const auto& [scene, kind] :
       {std::pair<std::string, std::string>{"box_push_tip", "tip"},
        std::pair<std::string, std::string>{"box_push_slide", "slide"}}) {
    const RealRun run = run_scene(scene);
    const std::vector<plot::PlotEvent> events = services::plot_events(run.outcome.result);
    REQUIRE_FALSE(run.outcome.result.body_events.empty());
    const double body_time = run.outcome.result.body_events.front().first(kind);
    REQUIRE(body_time > 0.0);
    for (const plot::PlotSpec& spec : run.prepared.plot_specs) {
      const plot::Figure figure = plot::make_figure(spec, run.outcome.result.trajectory, events);
      const std::vector<plot::EventMarker> shown = labelled(figure);
      INFO(scene << " " << spec.name << ": " << figure.events.size()
                 << " markers, labelled:" << describe(shown));
      // Figures that show the body's events label the body-level one, not each corner's.
      if (figure.events.empty()) continue;
      REQUIRE(shown.size() == 1);
      CHECK(shown[0].x == body_time);
      CHECK(shown[0].label.find(kind + " ") != std::string::npos);
    }
  }
}
