#include "core/body_events.hpp"

#include <algorithm>
#include <map>

#include "core/simulation.hpp"

namespace stiction::core {
namespace {

// The touching points span no area (one point, or on one line within `tolerance`) while an
// open point lies off that point or line: the body rests on a corner or an edge.
bool on_edge(const std::vector<Vec3>& touching, const std::vector<Vec3>& open, double tolerance) {
  const Vec3& a = touching.front();
  const auto far_from_a = [&](const Vec3& p) { return (p - a).norm() > tolerance; };
  const auto second = std::find_if(touching.begin(), touching.end(), far_from_a);
  if (second == touching.end()) return std::any_of(open.begin(), open.end(), far_from_a);
  const Vec3 direction = (*second - a).normalized();
  const auto off_line = [&](const Vec3& p) {
    const Vec3 d = p - a;
    return (d - d.dot(direction) * direction).norm() > tolerance;
  };
  if (std::any_of(touching.begin(), touching.end(), off_line)) return false;  // an area
  return std::any_of(open.begin(), open.end(), off_line);
}

// A stretch of one body state, from `start` to the next stretch's start; `uncertainty` that of
// the point events at `start` (the largest).
struct Segment {
  BodyState state;
  double start;
  double uncertainty = 0.0;
};

// The stretches with the states no longer than `resolution` (but the last) left out and equal
// neighbours joined, as SlipMonitor drops short sticks: corners breaking loose a rounding
// error or one step apart (each point's change is seen at a step) make no partial slip. A left-out
// state's time goes to the state before it (every point slips, sticks, is open, or is off the edge
// only once the last one is), but after `open` to the state after it (a landing is the first
// touch).
std::vector<Segment> without_short_states(const std::vector<Segment>& segments, double resolution) {
  std::vector<Segment> out;
  for (Segment s : segments) {
    if (!out.empty() && s.start - out.back().start <= resolution * (1.0 + 1e-9)) {
      if (out.size() == 1) {  // at the start: the body is in `s` from the first moment
        out.back().state = s.state;
        continue;
      }
      const Segment dropped = out.back();
      out.pop_back();
      if (out.back().state == BodyState::open) {
        s.start = dropped.start;
        s.uncertainty = dropped.uncertainty;
      }
    }
    if (!out.empty() && out.back().state == s.state) continue;
    out.push_back(s);
  }
  return out;
}

struct Point {
  const SlipHistory* history;
  std::vector<SlipInterval> intervals;
  std::size_t at = 0;  // the interval in force
};

}  // namespace

const char* body_state_name(BodyState state) {
  switch (state) {
    case BodyState::open:
      return "open";
    case BodyState::stick:
      return "stick";
    case BodyState::slide:
      return "slide";
    case BodyState::partial_slip:
      return "partial_slip";
    case BodyState::tip:
      return "tip";
    case BodyState::dropped:
      return "dropped";
  }
  return "open";
}

double BodyEventHistory::first(std::string_view kind) const {
  for (const BodyEvent& e : events) {
    if (e.kind == kind) return e.time;
  }
  return -1.0;
}

BodyState body_state(const std::vector<Vec3>& points, const std::vector<std::string>& states,
                     double tolerance, bool rolling) {
  std::vector<Vec3> touching, open;
  bool any_stick = false, any_slip = false;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (states[i] == "dropped") return BodyState::dropped;
    if (states[i] == "open") {
      open.push_back(points[i]);
      continue;
    }
    touching.push_back(points[i]);
    any_stick |= states[i] == "stick";
    any_slip |= states[i] == "slip";
  }
  if (touching.empty()) return BodyState::open;
  if (!rolling && on_edge(touching, open, tolerance)) return BodyState::tip;
  if (any_stick && any_slip) return BodyState::partial_slip;
  return any_slip ? BodyState::slide : BodyState::stick;
}

std::vector<BodyEventHistory> body_events(const std::vector<SlipHistory>& histories) {
  // The bodies' points, in the order of each body's first point.
  std::vector<std::string> order;
  // A pair's contact is a point of both its bodies, at its own place in each one's frame.
  struct Member {
    const SlipHistory* history;
    Vec3 local;
  };
  std::map<std::string, std::vector<Member>> by_body;
  const auto add = [&](const std::string& body, const SlipHistory& h, const Vec3& local) {
    auto& list = by_body[body];
    if (list.empty()) order.push_back(body);
    list.push_back({&h, local});
  };
  for (const SlipHistory& h : histories) {
    if (h.body.empty() || h.monitor.initial_state().empty()) continue;
    add(h.body, h, h.point);
    if (!h.other_body.empty()) add(h.other_body, h, h.other_point);
  }
  std::vector<BodyEventHistory> out;
  for (const std::string& name : order) {
    const std::vector<Member>& members = by_body[name];
    if (members.size() < 2) continue;
    BodyEventHistory body;
    body.body = name;
    std::vector<Point> points;
    std::vector<Vec3> local;
    bool rolling = false;
    for (const Member& m : members) {
      body.points.push_back(m.history->component);
      points.push_back({m.history, m.history->monitor.intervals()});
      local.push_back(m.local);
      rolling |= m.history->rolling;
    }
    double extent = 0.0;
    for (const Vec3& p : local) extent = std::max(extent, (p - local.front()).norm());
    const double tolerance = 1e-6 * extent;

    // Every moment some point changes state, in order; the body's state after each.
    std::vector<double> times;
    for (const Point& p : points) {
      for (std::size_t i = 1; i < p.intervals.size(); ++i) times.push_back(p.intervals[i].start);
    }
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    // How precisely each of those moments is known: the largest uncertainty of the point
    // events there (an interval starts at its event's time, bit for bit).
    std::map<double, double> uncertainty;
    for (const Point& p : points) {
      for (const SlipEvent& e : p.history->monitor.events()) {
        double& u = uncertainty[e.time];
        u = std::max(u, e.uncertainty);
      }
    }
    const auto uncertainty_at = [&](double t) {
      const auto it = uncertainty.find(t);
      return it != uncertainty.end() ? it->second : 0.0;
    };
    std::vector<std::string> states(points.size());
    const auto state_now = [&] {
      for (std::size_t i = 0; i < points.size(); ++i)
        states[i] = points[i].intervals[points[i].at].kind;
      return body_state(local, states, tolerance, rolling);
    };
    std::vector<Segment> segments{{state_now(), points.front().intervals.front().start, 0.0}};
    for (double t : times) {
      for (Point& p : points) {
        while (p.at + 1 < p.intervals.size() && p.intervals[p.at + 1].start <= t) ++p.at;
      }
      segments.push_back({state_now(), t, uncertainty_at(t)});
    }
    double end = segments.front().start;
    double resolution = 0.0;
    for (const Point& p : points) {
      end = std::max(end, p.intervals.back().end);
      resolution = std::max(resolution, p.history->monitor.resolution());
    }
    segments = without_short_states(segments, resolution);

    body.initial = body_state_name(segments.front().state);
    for (std::size_t k = 0; k < segments.size(); ++k) {
      const Segment& s = segments[k];
      const double until = k + 1 < segments.size() ? segments[k + 1].start : std::max(s.start, end);
      body.intervals.push_back({body_state_name(s.state), s.start, until});
      if (k == 0 || s.state == BodyState::dropped) continue;
      const BodyState before = segments[k - 1].state;
      const char* kind = s.state == BodyState::open  ? "lift_off"
                         : before == BodyState::open ? "land"
                                                     : body_state_name(s.state);
      body.events.push_back({kind, s.start, body_state_name(s.state), s.uncertainty});
    }
    out.push_back(std::move(body));
  }
  return out;
}

}  // namespace stiction::core
