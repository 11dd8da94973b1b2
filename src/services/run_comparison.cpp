#include "services/run_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "scene/toml_reader.hpp"

namespace stiction::services {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Errors below this fraction of a component's largest signal are rounding, not inaccuracy (a
// signal that stays at zero has a scale of rounding noise).
constexpr double kRounding = 1e-9;
// A final value's scale is never below this fraction of the largest scale of its class in
// the scene (a joint that never moved is judged against its mechanism's motion).
constexpr double kClassFloor = 1e-2;

template <typename... Numbers>
std::string format(const char* pattern, Numbers... numbers) {
  char text[240];
  std::snprintf(text, sizeof text, pattern, numbers...);
  return text;
}

bool is_event_class(const std::string& cls) {
  return cls == "first_stick" || cls == "last_stick" || cls == "first_slip" ||
         cls == "last_slip" || cls == "body_events" || cls == "event_counts";
}

// The class of a final value from its signal's name, for a body (admittance) column.
std::string body_class(const std::string& signal) {
  if (signal == "p") return "position";
  if (signal == "v") return "velocity";
  if (signal == "q") return "orientation";
  if (signal == "w") return "spin";
  if (signal == "theta") return "joint_angle";
  if (signal == "omega") return "joint_speed";
  return "element_state";
}

// Travelled path for these classes, largest magnitude for the others.
bool scaled_by_travel(const std::string& cls) {
  return cls == "position" || cls == "orientation" || cls == "joint_angle";
}

struct Owner {
  std::string component;
  bool body = false;
};

// The component a column belongs to: the longest component name that is a prefix of it up
// to a dot. A table of the names, looked up at each dot of the column, keeps this linear in
// the columns (40000 springs on one mass: issue 25's bound).
class Owners {
 public:
  explicit Owners(const core::Network& network) {
    for (const auto& i : network.impedances()) names_.emplace(i->name(), false);
    for (const auto& a : network.admittances()) names_[a->name()] = true;
  }
  Owner of(const std::string& column) const {
    for (auto dot = column.rfind('.'); dot != std::string::npos && dot > 0;
         dot = column.rfind('.', dot - 1)) {
      const auto it = names_.find(column.substr(0, dot));
      if (it != names_.end()) return {it->first, it->second};
    }
    return {};
  }

 private:
  std::unordered_map<std::string, bool> names_;
};

// First and last time of an event kind, its location uncertainty and its own time scale.
struct Occurrence {
  double time = kNaN;
  double located = 0.0;
  double scale = 0.0;
};

// An event's own time scale: the longer of the time since the element's previous event of
// the same kind (or the start) and the time to its next one (or the end). An onset under a
// ramp comes after a long hold, a slide that starts at once is followed by a long one, a
// stick at the end of a slide interrupted by bounces comes a whole slide after the start:
// the scale is the motion's, not the event's distance from t = 0, not the length of a bounce
// between two of its events, not the run's duration.
double phase_scale(const std::vector<double>& same_kind, std::size_t i, double end) {
  const double before = same_kind[i] - (i > 0 ? same_kind[i - 1] : 0.0);
  const double after = (i + 1 < same_kind.size() ? same_kind[i + 1] : end) - same_kind[i];
  return std::max(before, after);
}

// Per kind, the times of the events of that kind, in order.
template <typename Event>
std::map<std::string, std::vector<double>> times_by_kind(const std::vector<Event>& events) {
  std::map<std::string, std::vector<double>> times;
  for (const Event& e : events) times[e.kind].push_back(e.time);
  return times;
}

struct KindEvents {
  Occurrence first, last;
  std::size_t count = 0;
};

std::map<std::string, KindEvents> element_kinds(const core::SlipMonitor& m, double end) {
  std::map<std::string, KindEvents> kinds;
  const auto times = times_by_kind(m.events());
  std::map<std::string, std::size_t> index;
  for (const core::SlipEvent& e : m.events()) {
    KindEvents& k = kinds[e.kind];
    const Occurrence o{e.time, e.uncertainty, phase_scale(times.at(e.kind), index[e.kind]++, end)};
    if (std::isnan(k.first.time)) k.first = o;
    k.last = o;
  }
  for (const char* kind : {"stick", "slip", "open"}) {
    const std::size_t n = m.count(kind);
    if (n > 0) kinds[kind].count = n;
  }
  return kinds;
}

std::map<std::string, KindEvents> body_kinds(const core::BodyEventHistory& h, double end) {
  std::map<std::string, KindEvents> kinds;
  const auto times = times_by_kind(h.events);
  std::map<std::string, std::size_t> index;
  for (const core::BodyEvent& e : h.events) {
    KindEvents& k = kinds[e.kind];
    const Occurrence o{e.time, e.uncertainty, phase_scale(times.at(e.kind), index[e.kind]++, end)};
    if (std::isnan(k.first.time)) k.first = o;
    k.last = o;
    ++k.count;
  }
  return kinds;
}

class Comparer {
 public:
  Comparer(const core::Network& network, const ComparisonSetup& setup, RunComparison& out)
      : network_(network), setup_(setup), out_(out) {}

  // The first and last events of each kind of one component in both runs.
  void events(const std::string& component, const std::map<std::string, KindEvents>& mine,
              const std::map<std::string, KindEvents>& theirs, bool body) {
    std::set<std::string> kinds;
    for (const auto& [kind, k] : mine) kinds.insert(kind);
    for (const auto& [kind, k] : theirs) kinds.insert(kind);
    // The last event of a kind is the same event in both runs only when the whole sequences
    // agree: a last stick after one slip or bounce more is another stick (the paper's sphere
    // at 2e-6 s: 50 sticks in both runs, 24 slips against 25, last sticks 0.2 ms apart).
    bool sequences_agree = true;
    for (const std::string& kind : kinds) {
      const auto a = mine.find(kind);
      const auto b = theirs.find(kind);
      sequences_agree = sequences_agree && (a != mine.end() ? a->second.count : 0) ==
                                               (b != theirs.end() ? b->second.count : 0);
    }
    for (const std::string& kind : kinds) {
      const auto a = mine.find(kind);
      const auto b = theirs.find(kind);
      const KindEvents none;
      const KindEvents& ka = a != mine.end() ? a->second : none;
      const KindEvents& kb = b != theirs.end() ? b->second : none;
      const bool counts_agree = ka.count == kb.count;
      if (!counts_agree) {
        CountDifference d{component, kind, ka.count, kb.count,
                          setup_.rule.judges(component, "event_counts")};
        if (d.judged) {
          out_.reasons.push_back(component + ": " + std::to_string(d.run) + " " + kind +
                                 " at " + setup_.run_label + ", " + std::to_string(d.other) +
                                 " in " + setup_.other_label);
        }
        out_.not_converged.push_back(d);
      }
      // Only kinds the element's law has (stick, slip) or a body's events are timed; opens
      // (touch-downs) are counted, their times are the contact's bounces.
      if (!body && kind != "stick" && kind != "slip") continue;
      const std::string first_cls = body ? "body_events" : "first_" + kind;
      const std::string last_cls = body ? "body_events" : "last_" + kind;
      event(component, kind, "first_" + kind, first_cls, ka.first, kb.first, "");
      // With any count apart, the last events are not the same event in both runs.
      const bool one_event = ka.count <= 1 && kb.count <= 1;
      if (!one_event) {
        event(component, kind, "last_" + kind, last_cls, ka.last, kb.last,
              sequences_agree ? "" : "counts not converged");
      }
    }
  }

  void finals(const core::RunResult& run, const core::RunResult& other) {
    const core::Trajectory& a = run.trajectory;
    const core::Trajectory& b = other.trajectory;
    if (a.row_count() == 0 || b.row_count() == 0 || a.column_count() != b.column_count()) return;
    const int la = a.row_count() - 1, lb = b.row_count() - 1;
    const MotionScales* s = setup_.scales;
    struct Column {
      Owner owner;
      std::string cls;
      double scale = 0.0;
    };
    std::vector<Column> columns(static_cast<std::size_t>(a.column_count()));
    const Owners owners(network_);
    std::map<std::string, double> class_largest, component_largest;
    for (int c = 1; c < a.column_count(); ++c) {
      Column& col = columns[c];
      const std::string& name = a.columns()[c];
      col.owner = owners.of(name);
      const std::string signal = signal_of(name);
      const std::string tail = signal.substr(std::min(signal.size(), col.owner.component.size() + 1));
      col.cls = col.owner.body ? body_class(tail) : "element_state";
      if (s != nullptr) {
        const auto cc = static_cast<std::size_t>(c);
        col.scale = scaled_by_travel(col.cls) ? s->travel(cc) : s->signal_largest(cc);
        double& cl = class_largest[col.cls];
        cl = std::max(cl, col.scale);
        double& comp = component_largest[col.owner.component];
        comp = std::max(comp, std::max(s->signal_largest(cc), s->travel(cc)));
      }
    }
    for (int c = 1; c < a.column_count(); ++c) {
      const Column& col = columns[c];
      ComparedQuantity q;
      q.name = a.columns()[c];
      q.component = col.owner.component;
      q.cls = col.cls;
      q.value = a.at(la, c);
      q.other = b.at(lb, c);
      const double diff = std::abs(q.value - q.other);
      if (std::isfinite(diff)) q.error = setup_.final_factor * diff;
      q.scale = std::max(col.scale, kClassFloor * class_largest[col.cls]);
      q.tolerance = setup_.rule.tolerance(col.cls) * q.scale +
                    kRounding * component_largest[col.owner.component];
      q.judged = setup_.rule.judges(q.component, q.cls);
      if (q.judged) {
        out_.judged.push_back(q.name);
        const double rel = q.relative_error();
        if (!(rel <= out_.worst_final)) out_.worst_final = rel;
        worst(rel, q.name);
        if (!q.within()) {
          out_.reasons.push_back(
              q.name + format(" = %.7g has an estimated error of %.2g, above %g of its scale %.3g",
                              q.value, q.error ? *q.error : kNaN, setup_.rule.tolerance(q.cls),
                              q.scale));
        }
      }
      out_.finals.push_back(q);
    }
  }

 private:
  void worst(double rel, const std::string& name) {
    if (!(rel <= worst_) || out_.worst_name.empty()) {
      worst_ = rel;
      out_.worst_name = name;
    }
  }

  void event(const std::string& component, const std::string& kind, const std::string& which,
             const std::string& cls, const Occurrence& mine, const Occurrence& theirs,
             const std::string& not_comparable) {
    if (std::isnan(mine.time) && std::isnan(theirs.time)) return;
    ComparedQuantity q;
    q.name = component + "." + which;
    q.component = component;
    q.cls = cls;
    q.kind = kind;
    q.value = mine.time;
    q.other = theirs.time;
    q.located = mine.located;
    q.scale = std::isnan(mine.time) ? theirs.scale : mine.scale;
    q.tolerance = setup_.rule.tolerance(cls) * q.scale;
    q.note = not_comparable;
    if (std::isnan(mine.time)) {
      q.note = "only in " + setup_.other_label;
    } else if (std::isnan(theirs.time)) {
      q.note = "only in " + setup_.run_label;
    } else if (not_comparable.empty()) {
      q.error = std::max(setup_.event_factor * std::abs(mine.time - theirs.time), mine.located);
    }
    q.judged = not_comparable.empty() && setup_.rule.judges(component, cls);
    if (q.judged) {
      out_.judged.push_back(q.name);
      const double rel = q.relative_error();
      if (!(rel <= out_.worst_event)) out_.worst_event = rel;
      worst(rel, q.name);
      if (!q.error) {
        out_.reasons.push_back(component + ": " + which.substr(0, which.find('_')) + " " + kind +
                               " " + q.note);
      } else if (!q.within()) {
        out_.reasons.push_back(component + ": " + which.substr(0, which.find('_')) + " " + kind +
                               format(" at t = %.7g s has an estimated error of %.2g s, above "
                                      "%.2g s (%g of its time scale)",
                                      q.value, *q.error, q.tolerance,
                                      setup_.rule.tolerance(cls)));
      }
    }
    out_.events.push_back(q);
  }

  const core::Network& network_;
  const ComparisonSetup& setup_;
  RunComparison& out_;
  double worst_ = 0.0;
};

}  // namespace

const std::vector<std::string>& quantity_classes() {
  static const std::vector<std::string> classes = {
      "first_stick", "last_stick", "first_slip", "last_slip",   "body_events",
      "event_counts", "position",  "velocity",   "orientation", "spin",
      "joint_angle", "joint_speed", "element_state"};
  return classes;
}

const std::vector<std::string>& default_judged_classes() {
  static const std::vector<std::string> classes = {
      "first_stick", "last_stick", "first_slip",  "last_slip", "body_events",
      "position",    "velocity",   "orientation", "spin",      "joint_angle", "joint_speed"};
  return classes;
}

bool JudgeRule::judges(const std::string& component, const std::string& cls) const {
  const std::string specific = component + "." + cls;
  if (ignore.count(specific) != 0) return false;
  if (judge.count(specific) != 0) return true;
  return classes.count(cls) != 0;
}

double JudgeRule::tolerance(const std::string& cls) const {
  const auto it = tolerances.find(cls);
  if (it != tolerances.end()) return it->second;
  return is_event_class(cls) ? event_tolerance : final_tolerance;
}

JudgeRule read_judge_rule(const scene::Scene& scene) {
  JudgeRule rule;
  const auto& defaults = default_judged_classes();
  rule.classes.insert(defaults.begin(), defaults.end());
  scene::TableReader root(scene.document, "");
  if (!root.has("accuracy")) return rule;
  if (!scene.document.get("accuracy")->is_table()) root.fail("accuracy", "expected a table");
  scene::TableReader r = *root.subtable("accuracy");
  const auto& known = quantity_classes();
  const auto is_class = [&](const std::string& c) {
    return std::find(known.begin(), known.end(), c) != known.end();
  };
  std::string known_list;
  for (const auto& c : known) known_list += (known_list.empty() ? "" : ", ") + c;
  std::set<std::string> components;
  for (const auto& a : scene.network->admittances()) components.insert(a->name());
  for (const auto& i : scene.network->impedances()) components.insert(i->name());
  // CLASS, or COMPONENT.CLASS for one component's quantities.
  const auto entry = [&](const char* key, const std::string& e, bool& specific) {
    if (is_class(e)) {
      specific = false;
      return;
    }
    const auto dot = e.rfind('.');
    if (dot != std::string::npos && is_class(e.substr(dot + 1)) &&
        components.count(e.substr(0, dot)) != 0) {
      specific = true;
      return;
    }
    r.fail(key, "'" + e + "' is neither a quantity class (" + known_list +
                    ") nor COMPONENT.CLASS with a component of the scene");
  };
  for (const std::string& e : r.strings("judge")) {
    bool specific = false;
    entry("judge", e, specific);
    (specific ? rule.judge : rule.classes).insert(e);
  }
  for (const std::string& e : r.strings("ignore")) {
    bool specific = false;
    entry("ignore", e, specific);
    if (specific) {
      rule.ignore.insert(e);
    } else {
      rule.classes.erase(e);
    }
  }
  const auto relative = [&](scene::TableReader& t, const std::string& key, double fallback) {
    const double v = t.positive(key, fallback);
    if (!(v < 1.0)) t.fail(key, "is a relative error: must be > 0 and < 1");
    return v;
  };
  if (r.has("tolerance")) {
    const double all = relative(r, "tolerance", 1e-3);
    rule.event_tolerance = rule.final_tolerance = all;
  }
  if (auto t = r.subtable("tolerances")) {
    for (const auto& [key, value] : t->table()) {
      const std::string cls(key.str());
      if (!is_class(cls)) t->fail(cls, "not a quantity class (" + known_list + ")");
      rule.tolerances[cls] = relative(*t, cls, 1e-3);
    }
    t->finish();
  }
  r.finish();
  return rule;
}

std::string signal_of(const std::string& column) {
  const auto dot = column.rfind('.');
  if (dot == std::string::npos) return column;
  const std::string last = column.substr(dot + 1);
  const bool axis = last == "x" || last == "y" || last == "z" || last == "w" ||
                    (!last.empty() && std::all_of(last.begin(), last.end(),
                                                  [](char ch) { return ch >= '0' && ch <= '9'; }));
  return axis ? column.substr(0, dot) : column;
}

MotionScales::MotionScales(const core::Trajectory& trajectory) {
  set_columns(trajectory.columns());
  for (int r = 0; r < trajectory.row_count(); ++r) {
    write(trajectory.row(r), 1, static_cast<std::size_t>(trajectory.column_count()));
  }
}

void MotionScales::set_columns(const std::vector<std::string>& columns) {
  std::map<std::string, int> groups;
  group_.clear();
  for (const std::string& c : columns) {
    const auto [it, added] = groups.emplace(signal_of(c), static_cast<int>(groups.size()));
    group_.push_back(it->second);
  }
  travel_.assign(groups.size(), 0.0);
  group_largest_.assign(groups.size(), 0.0);
  largest_.assign(columns.size(), 0.0);
  have_previous_ = false;
}

void MotionScales::write(const double* rows, std::size_t count, std::size_t columns) {
  if (largest_.size() != columns) {
    // Without names every column is its own signal.
    largest_.assign(columns, 0.0);
    group_.resize(columns);
    for (std::size_t c = 0; c < columns; ++c) group_[c] = static_cast<int>(c);
    travel_.assign(columns, 0.0);
    group_largest_.assign(columns, 0.0);
    have_previous_ = false;
  }
  std::vector<double> step(travel_.size());
  for (std::size_t r = 0; r < count; ++r) {
    const double* row = rows + r * columns;
    std::fill(step.begin(), step.end(), 0.0);
    for (std::size_t c = 0; c < columns; ++c) {
      if (!std::isfinite(row[c])) continue;
      largest_[c] = std::max(largest_[c], std::abs(row[c]));
      const auto g = static_cast<std::size_t>(group_[c]);
      group_largest_[g] = std::max(group_largest_[g], std::abs(row[c]));
      if (have_previous_ && std::isfinite(previous_[c])) {
        const double d = row[c] - previous_[c];
        step[g] += d * d;
      }
    }
    for (std::size_t g = 0; g < step.size(); ++g) travel_[g] += std::sqrt(step[g]);
    previous_.assign(row, row + columns);
    have_previous_ = true;
  }
}

double MotionScales::largest(std::size_t column) const {
  return column < largest_.size() ? largest_[column] : 0.0;
}

double MotionScales::travel(std::size_t column) const {
  return column < group_.size() ? travel_[static_cast<std::size_t>(group_[column])] : 0.0;
}

double MotionScales::signal_largest(std::size_t column) const {
  return column < group_.size() ? group_largest_[static_cast<std::size_t>(group_[column])] : 0.0;
}

double ComparedQuantity::relative_error() const {
  if (!error) return kInf;
  if (!(scale > 0.0)) return *error > tolerance ? kInf : 0.0;
  return *error / scale;
}

RunComparison compare_runs(const core::Network& network, const core::RunResult& run,
                           const core::RunResult& other, const ComparisonSetup& setup) {
  RunComparison out;
  Comparer comparer(network, setup, out);
  const auto end_of = [](const core::RunResult& r) {
    const core::Trajectory& t = r.trajectory;
    return t.row_count() > 0 ? t.at(t.row_count() - 1, 0) : 0.0;
  };
  const double end = end_of(run), other_end = end_of(other);
  // The other run's histories by name: linear in the elements, however many.
  std::unordered_map<std::string, const core::SlipHistory*> other_elements;
  for (const core::SlipHistory& f : other.slip_events) other_elements.emplace(f.component, &f);
  for (const core::SlipHistory& h : run.slip_events) {
    const auto f = other_elements.find(h.component);
    const auto theirs = f != other_elements.end() ? element_kinds(f->second->monitor, other_end)
                                                  : std::map<std::string, KindEvents>{};
    comparer.events(h.component, element_kinds(h.monitor, end), theirs, false);
  }
  std::unordered_map<std::string, const core::BodyEventHistory*> other_bodies;
  for (const core::BodyEventHistory& f : other.body_events) other_bodies.emplace(f.body, &f);
  for (const core::BodyEventHistory& h : run.body_events) {
    const auto f = other_bodies.find(h.body);
    const auto theirs = f != other_bodies.end() ? body_kinds(*f->second, other_end)
                                                : std::map<std::string, KindEvents>{};
    comparer.events(h.body, body_kinds(h, end), theirs, true);
  }
  comparer.finals(run, other);
  return out;
}

}  // namespace stiction::services
