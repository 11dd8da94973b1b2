// Labelled events get their label at their mark (over it, or beside it joined by a leader,
// or stacked in rows), never overlapping another text; events that are not labelled are
// drawn without one; a label with no room is reported in the layout, not dropped silently.
// Tested on generated figures: random clusters of 1..20 events on random figure sizes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "plot/figure.hpp"

using namespace stiction;
namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(STICTION_TEST_OUTPUT_DIR) / "event_labels";

double distance_to_box(plot::Point p, const plot::Rect& r) {
  const double dx = std::max({r.x0 - p.x, 0.0, p.x - r.x1});
  const double dy = std::max({r.y0 - p.y, 0.0, p.y - r.y1});
  return std::hypot(dx, dy);
}

struct Counts {
  int labelled = 0, placed = 0, with_leader = 0;
};

// Every labelled event's label is at its mark or joined to it; no other label meets it.
Counts check_event_labels(const plot::Figure& figure, const plot::FigureLayout& layout) {
  Counts counts;
  const std::vector<std::string> problems = plot::layout_problems(layout);
  for (const std::string& p : problems) UNSCOPED_INFO(p);
  CHECK(problems.empty());
  REQUIRE(!layout.panels.empty());
  const plot::Rect& top = layout.panels.front();
  int label_texts = 0;
  for (const plot::TextBox& t : layout.texts) label_texts += t.role == plot::TextRole::event_label;
  for (const plot::EventLabelReport& e : layout.event_labels) {
    REQUIRE(e.event >= 0);
    REQUIRE(e.event < static_cast<int>(figure.events.size()));
    CHECK(figure.events[e.event].labelled);
    ++counts.labelled;
    CHECK(e.mark.y == top.y0);
    CHECK(e.mark.x >= top.x0 - 1);
    CHECK(e.mark.x <= top.x1 + 1);
    if (e.text < 0) continue;  // no room: reported
    ++counts.placed;
    REQUIRE(e.text < static_cast<int>(layout.texts.size()));
    const plot::TextBox& label = layout.texts[e.text];
    CHECK(label.role == plot::TextRole::event_label);
    CHECK(label.box.y1 <= top.y0);  // above the top panel
    const bool over_mark = e.mark.x >= label.box.x0 - 3 && e.mark.x <= label.box.x1 + 3;
    if (e.leader.empty()) {
      INFO("label '" << label.text << "' at [" << label.box.x0 << ", " << label.box.x1
                     << "] for a mark at " << e.mark.x);
      CHECK(over_mark);
    } else {
      ++counts.with_leader;
      CHECK(e.leader.front().x == e.mark.x);
      CHECK(e.leader.front().y == e.mark.y);
      CHECK(distance_to_box(e.leader.back(), label.box) < 0.5 * label.box.height());
    }
  }
  CHECK(label_texts == counts.placed);
  // Events that are not labelled have no report and no label.
  const long wanted = std::count_if(figure.events.begin(), figure.events.end(),
                                    [](const plot::EventMarker& e) { return e.labelled; });
  CHECK(counts.labelled <= wanted);
  return counts;
}

plot::Figure random_figure(std::mt19937& rng, int events) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  plot::Figure figure;
  figure.title = unit(rng) < 0.5 ? "Events in clusters" : "";
  if (unit(rng) < 0.3) {
    figure.print = plot::Figure::Print{60 + 120 * unit(rng), 50 + 80 * unit(rng), 6 + 4 * unit(rng),
                                       100 + 300 * unit(rng)};
  } else {
    figure.width = 400 + static_cast<int>(2000 * unit(rng));
    figure.height = 300 + static_cast<int>(1300 * unit(rng));
  }
  const double duration = 0.5 + 20 * unit(rng);
  const int panels = 1 + static_cast<int>(3 * unit(rng));
  for (int p = 0; p < panels; ++p) {
    plot::Panel& panel = figure.panels.emplace_back();
    panel.label = "signal " + std::to_string(p);
    panel.unit = "m";
    plot::Series& s = panel.series.emplace_back();
    for (int i = 0; i <= 400; ++i) {
      s.x.push_back(duration * i / 400.0);
      s.y.push_back(std::sin(6.0 * i / 400.0 + p));
    }
  }
  // Events in 1..4 clusters, each a few percent of the run wide.
  std::vector<double> centres(1 + static_cast<int>(4 * unit(rng)));
  for (double& c : centres) c = duration * unit(rng);
  const char* kinds[] = {"stick", "slip", "tip"};
  for (int k = 0; k < events; ++k) {
    const double c = centres[static_cast<std::size_t>(unit(rng) * centres.size())];
    const double t = std::clamp(c + duration * 0.03 * (unit(rng) - 0.5), 0.0, duration);
    const std::string kind = kinds[static_cast<int>(3 * unit(rng))];
    std::string name = unit(rng) < 0.3 ? "a_rather_long_element_name_" + std::to_string(k)
                                       : "joint" + std::to_string(k % 3);
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", t);
    figure.events.push_back({t, name + " " + kind + ": t = " + time + " s", kind, unit(rng) < 0.8});
  }
  return figure;
}

}  // namespace

TEST_CASE("event labels sit at their marks, never overlap, and are reported when left out",
          "[plot][events]") {
  std::mt19937 rng(2101);
  fs::create_directories(kOut);
  Counts total;
  for (int i = 0; i < 60; ++i) {
    const int events = 1 + i % 20;
    const plot::Figure figure = random_figure(rng, events);
    INFO("figure " << i << ": " << events << " events, " << plot::pixel_size(figure).width << " x "
                   << plot::pixel_size(figure).height);
    plot::FigureLayout layout;
    if (i < 6) {
      layout = plot::write_figure(figure, kOut / ("random_" + std::to_string(i) + ".png"),
                                  plot::Format::png);
    } else {
      plot::render(figure, &layout);
    }
    const Counts c = check_event_labels(figure, layout);
    total.labelled += c.labelled;
    total.placed += c.placed;
    total.with_leader += c.with_leader;
  }
  // Most labels find room (the clusters are tight and up to 20 events share a figure).
  CHECK(total.placed >= 0.6 * total.labelled);
  CHECK(total.with_leader > 0);
  WARN("labelled " << total.labelled << ", placed " << total.placed << ", with a leader "
                   << total.with_leader);
}

TEST_CASE("a few labelled events always get their labels", "[plot][events]") {
  std::mt19937 rng(77);
  for (int i = 0; i < 30; ++i) {
    plot::Figure figure = random_figure(rng, 1 + i % 4);
    if (plot::pixel_size(figure).width < 700) continue;
    for (plot::EventMarker& e : figure.events) e.labelled = true;
    plot::FigureLayout layout;
    plot::render(figure, &layout);
    const Counts c = check_event_labels(figure, layout);
    INFO("figure " << i);
    CHECK(c.placed == c.labelled);
    if (c.placed != c.labelled) {
      fs::create_directories(kOut);
      std::string name = "few_";
      name += std::to_string(i);
      name += ".png";
      plot::write_figure(figure, kOut / name, plot::Format::png);
    }
  }
}

TEST_CASE("two events at one time stack their labels over the mark", "[plot][events]") {
  plot::Figure figure;
  figure.panels.push_back({"v", "m/s", false, {{"", {0.0, 10.0}, {0.0, 1.0}, {}}}, {}, {}, {}});
  figure.events.push_back({4.5, "joint0 stick: t = 4.5 s", "stick"});
  figure.events.push_back({4.5, "joint1 stick: t = 4.5 s", "stick"});
  figure.events.push_back({2.0, "unlabelled", "slip", false});
  plot::FigureLayout layout;
  plot::render(figure, &layout);
  const Counts c = check_event_labels(figure, layout);
  CHECK(c.placed == 2);
  REQUIRE(layout.event_labels.size() == 2);
  for (const plot::TextBox& t : layout.texts) CHECK(t.text != "unlabelled");
  // The key says what the unlabelled tick is.
  CHECK(std::any_of(layout.texts.begin(), layout.texts.end(),
                    [](const plot::TextBox& t) { return t.text == "slip"; }));
}
