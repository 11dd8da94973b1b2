// The roles of a run's events (plot/event_selection.hpp) and which of them a figure labels:
// hand-made histories (a bouncing contact, a settling joint, a body that slides, tips and
// lands), generated histories of many elements checked against a reference computed from
// their state intervals, and the selectors of `events` / `labels`.
#include <catch2/catch.hpp>
#include <map>
#include <random>
#include <set>

#include "plot/plot_spec.hpp"
#include "synthetic.hpp"

using namespace stiction;
using plot::ClassifiedEvent;
using plot::PlotEvent;

namespace {

const ClassifiedEvent& at(const std::vector<ClassifiedEvent>& events, const std::string& element,
                          double time) {
  for (const ClassifiedEvent& e : events) {
    if (e.event.element == element && e.event.time == time) return e;
  }
  FAIL("no event of " << element << " at " << time);
  throw;
}

std::vector<std::string> labels_of(const plot::Figure& figure) {
  std::vector<std::string> out;
  for (const plot::EventMarker& e : figure.events) {
    if (e.labelled) out.push_back(e.label);
  }
  return out;
}

}  // namespace

TEST_CASE("a contact that lands, bounces, sticks and bounces on: one label, the first stick",
          "[plot][events]") {
  // sphere_roll's shape: starts in the air, lands sliding, lifts off, ..., sticks (rolling
  // starts), slips into a lift-off, then touches down stuck again and again.
  const std::vector<PlotEvent> events{
      {"ground", "slip", 0.02, true}, {"ground", "open", 0.021},  {"ground", "slip", 0.06},
      {"ground", "open", 0.061},      {"ground", "slip", 0.5841}, {"ground", "stick", 0.5843},
      {"ground", "slip", 0.5846},     {"ground", "open", 0.5847}, {"ground", "stick", 0.62},
      {"ground", "open", 0.621},      {"ground", "stick", 0.65},  {"ground", "open", 0.651}};
  const std::vector<ClassifiedEvent> c = plot::classify_events(events);
  REQUIRE(c.size() == 7);  // the lift-offs are not marked
  for (const ClassifiedEvent& e : c) {
    INFO(e.event.kind << " at " << e.event.time);
    CHECK(e.roles.important == (e.event.time == 0.5843));
    CHECK(e.roles.touch_down == (e.event.time != 0.5843 && e.event.time != 0.5846));
  }
  CHECK(at(c, "ground", 0.5843).roles.first_stick);
  CHECK_FALSE(at(c, "ground", 0.5843).roles.final_stop);  // it bounces on
  CHECK_FALSE(at(c, "ground", 0.5846).roles.break_away);  // slips into a lift-off: a bounce
  CHECK(plot::event_word(at(c, "ground", 0.02)) == "touch-down");
  CHECK(plot::event_label(at(c, "ground", 0.5843), false) == "stick 0.5843 s");
  CHECK(plot::event_label(at(c, "ground", 0.5843), true) == "ground stick 0.5843 s");
}

TEST_CASE("a settling joint: break-aways, the first stick and the final stop are labelled",
          "[plot][events]") {
  // two_link's joint 1: moves at 1 s, sticks at 2.62 s, is dragged at 4.46 s, settles in
  // short stick-slips and stops at 4.65 s.
  const std::vector<PlotEvent> events{
      {"j", "slip", 1.0},   {"j", "stick", 2.62},  {"j", "slip", 4.455}, {"j", "stick", 4.467},
      {"j", "slip", 4.517}, {"j", "stick", 4.532}, {"j", "slip", 4.645}, {"j", "stick", 4.651}};
  const std::vector<ClassifiedEvent> c = plot::classify_events(events);
  std::vector<double> important;
  for (const ClassifiedEvent& e : c) {
    if (e.roles.important) important.push_back(e.event.time);
  }
  CHECK(important == std::vector<double>{1.0, 2.62, 4.455, 4.651});
  CHECK(at(c, "j", 4.651).roles.final_stop);
  CHECK(plot::event_word(at(c, "j", 4.651)) == "stop");
  CHECK(plot::event_word(at(c, "j", 4.467)) == "stick");
  CHECK(plot::event_label(at(c, "j", 1.0), false) == "slip 1 s");
  // A single stick that lasts to the end is the first stick and the stop: "stick".
  const auto once = plot::classify_events({{"k", "slip", 0.5}, {"k", "stick", 1.25}});
  CHECK(once[1].roles.first_stick);
  CHECK(once[1].roles.final_stop);
  CHECK(plot::event_word(once[1]) == "stick");
  // A box dropped that sticks where it lands: the touch-down is its stop, labelled.
  const auto dropped = plot::classify_events({{"c", "stick", 0.3, true}});
  CHECK(dropped[0].roles.touch_down);
  CHECK_FALSE(dropped[0].roles.first_stick);
  CHECK(dropped[0].roles.important);
}

TEST_CASE("body-level events are labelled and speak for their contact points", "[plot][events]") {
  PlotEvent slide{"crate", "slide", 2.45};
  slide.body_level = true;
  PlotEvent tip{"box", "tip", 1.633};
  tip.body_level = true;
  PlotEvent lift{"box", "lift_off", 2.1};
  lift.body_level = true;
  PlotEvent land{"box", "land", 2.4};
  land.body_level = true;
  PlotEvent crate_stick{"crate", "stick", 3.5};
  crate_stick.body_level = true;
  std::vector<PlotEvent> events{slide, tip, lift, land, crate_stick};
  // The crate's corners slip with it; the lone peg is no body's.
  for (const char* corner : {"c0", "c1", "c2", "c3"}) {
    PlotEvent e{corner, "slip", 2.45};
    e.body = "crate";
    events.push_back(e);
  }
  events.push_back({"peg", "slip", 0.7});
  const std::vector<ClassifiedEvent> c = plot::classify_events(events);
  CHECK(at(c, "box", 1.633).roles.important);
  CHECK(at(c, "box", 2.1).roles.important);
  CHECK(at(c, "box", 2.4).roles.important);
  CHECK(at(c, "crate", 2.45).roles.important);
  CHECK(at(c, "crate", 2.45).roles.break_away);
  CHECK(at(c, "crate", 3.5).roles.final_stop);
  CHECK(at(c, "c2", 2.45).roles.break_away);
  CHECK_FALSE(at(c, "c2", 2.45).roles.important);  // its body tells it
  CHECK(at(c, "peg", 0.7).roles.important);
  CHECK(plot::event_word(at(c, "box", 2.1)) == "lift-off");
  CHECK(plot::event_word(at(c, "box", 1.633)) == "tip");
  CHECK(plot::event_word(at(c, "crate", 3.5)) == "stick");
  // A contact of a body without body-level events is labelled as any element.
  PlotEvent lone{"d0", "slip", 0.2};
  lone.body = "drum";
  CHECK(plot::classify_events({lone})[0].roles.important);

  // On a figure: body events marked with their kind, labelled with the body's name.
  const core::Trajectory run = plot::testing::sphere_run(4.0);
  plot::PlotSpec spec = plot::paper_fig4_spec();
  const plot::Figure figure = plot::make_figure(spec, run, events);
  CHECK(figure.events.size() == events.size());
  const std::vector<std::string> labels = labels_of(figure);
  CHECK(labels == std::vector<std::string>{"peg slip 0.7 s", "box tip 1.633 s",
                                           "box lift-off 2.1 s", "box land 2.4 s",
                                           "crate slide 2.45 s", "crate stick 3.5 s"});
  CHECK(figure.events[1].kind == "tip");
  // Selected by the body's name, or by kind.
  spec.only_events = {"box"};
  CHECK(plot::make_figure(spec, run, events).events.size() == 3);
  spec.only_events = {"box.tip", "crate.slide"};
  CHECK(labels_of(plot::make_figure(spec, run, events)) ==
        std::vector<std::string>{"box tip 1.633 s", "crate slide 2.45 s"});
  spec.only_events.clear();
  spec.labels.mode = plot::EventLabels::Mode::listed;
  spec.labels.selectors = {"c1", "box.land"};
  CHECK(labels_of(plot::make_figure(spec, run, events)) ==
        std::vector<std::string>{"box land 2.4 s", "c1 slip 2.45 s"});
  spec.labels.mode = plot::EventLabels::Mode::none;
  CHECK(labels_of(plot::make_figure(spec, run, events)).empty());
}

TEST_CASE("generated histories of many elements: roles agree with their state intervals",
          "[plot][events]") {
  // Random element histories (stick / slip / open states, some starting in the air, some
  // ending stuck), shuffled together; the roles are checked against a reference that reads
  // each element's sequence of states.
  std::mt19937 rng(2111);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<PlotEvent> events;
    std::map<std::string, std::vector<std::string>> states;  // per element, from t = 0
    std::map<std::string, std::vector<double>> times;        // times of the changes
    const int elements = std::uniform_int_distribution<int>(1, 6)(rng);
    for (int k = 0; k < elements; ++k) {
      const std::string name = "e" + std::to_string(k);
      std::vector<std::string> s{std::vector<std::string>{
          "stick", "slip", "open"}[std::uniform_int_distribution<int>(0, 2)(rng)]};
      double t = 0.0;
      const int changes = std::uniform_int_distribution<int>(0, 12)(rng);
      for (int i = 0; i < changes; ++i) {
        std::vector<std::string> next;
        for (const char* candidate : {"stick", "slip", "open"}) {
          if (candidate != s.back()) next.push_back(candidate);
        }
        s.push_back(next[std::uniform_int_distribution<int>(0, 1)(rng)]);
        t += std::uniform_real_distribution<double>(1e-3, 0.5)(rng);
        times[name].push_back(t);
        PlotEvent e{name, s.back(), t};
        e.touch_down = i == 0 && s.front() == "open";
        events.push_back(e);
      }
      states[name] = s;
    }
    std::shuffle(events.begin(), events.end(), rng);
    const std::vector<ClassifiedEvent> c = plot::classify_events(events);
    // The reference: the state before and after each change.
    std::size_t expected_count = 0;
    for (const auto& [name, s] : states) {
      int first_stick = -1;
      for (std::size_t i = 1; i < s.size(); ++i) {
        if (s[i] == "open") continue;
        ++expected_count;
        const ClassifiedEvent& e = at(c, name, times[name][i - 1]);
        INFO("trial " << trial << ": " << name << " change " << i << " " << s[i - 1] << " -> "
                      << s[i]);
        const bool touch_down = s[i - 1] == "open";
        CHECK(e.roles.touch_down == touch_down);
        const bool first = s[i] == "stick" && !touch_down && first_stick < 0;
        if (first) first_stick = static_cast<int>(i);
        CHECK(e.roles.first_stick == first);
        CHECK(e.roles.final_stop == (s[i] == "stick" && i + 1 == s.size()));
        const bool from_labelled = (i == 1 && s[0] == "stick") ||
                                   (first_stick >= 0 && static_cast<int>(i) == first_stick + 1);
        const bool bounce = i + 1 < s.size() && s[i + 1] == "open";
        CHECK(e.roles.break_away == (s[i] == "slip" && from_labelled && !bounce));
        CHECK(e.roles.important ==
              (e.roles.first_stick || e.roles.final_stop || e.roles.break_away));
      }
    }
    CHECK(c.size() == expected_count);
    CHECK(
        std::is_sorted(c.begin(), c.end(), [](const ClassifiedEvent& a, const ClassifiedEvent& b) {
          return a.event.time < b.event.time;
        }));
  }
}

TEST_CASE("event selectors", "[plot][events]") {
  std::string why;
  auto parsed = plot::parse_event_selector("ground.first_stick", why);
  REQUIRE(parsed);
  CHECK(parsed->element == "ground");
  CHECK(parsed->what == "first_stick");
  parsed = plot::parse_event_selector("joint0_friction", why);
  REQUIRE(parsed);
  CHECK(parsed->what.empty());
  CHECK(plot::parse_event_selector("box.tip", why));
  CHECK(plot::parse_event_selector("ground.stick_time", why));
  CHECK_FALSE(plot::parse_event_selector("ground.stik", why));
  CHECK_THAT(why, Catch::Contains("unknown event 'stik'") && Catch::Contains("final_stop"));
  CHECK_FALSE(plot::parse_event_selector(".stick", why));
  CHECK_FALSE(plot::parse_event_selector("", why));

  const auto c = plot::classify_events(
      {{"g", "slip", 0.1}, {"g", "stick", 0.2}, {"g", "slip", 0.3}, {"g", "stick", 0.4}});
  const auto picks = [&](const std::string& text) {
    std::string unused;
    const auto s = plot::parse_event_selector(text, unused);
    std::vector<double> out;
    for (const ClassifiedEvent& e : c) {
      if (plot::selects(*s, e)) out.push_back(e.event.time);
    }
    return out;
  };
  CHECK(picks("g") == std::vector<double>{0.1, 0.2, 0.3, 0.4});
  CHECK(picks("g.stick") == std::vector<double>{0.2, 0.4});
  CHECK(picks("g.first_stick") == std::vector<double>{0.2});
  CHECK(picks("g.stick_time") == std::vector<double>{0.2});
  CHECK(picks("g.slip_time") == std::vector<double>{0.1});
  CHECK(picks("g.final_stop") == std::vector<double>{0.4});
  CHECK(picks("g.break_away") == std::vector<double>{0.1, 0.3});
  CHECK(picks("h").empty());
}
