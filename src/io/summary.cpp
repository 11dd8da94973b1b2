#include "io/summary.hpp"

#include <string_view>
#include <unordered_set>

#include "core/events.hpp"
#include "io/atomic_file.hpp"
#include "io/json_members.hpp"

namespace stiction::io {

namespace {

// The first slip event that follows a stick (the initial state counts), or -1.
double first_breakaway(const core::SlipMonitor& monitor) {
  std::string previous = monitor.initial_state();
  for (const core::SlipEvent& e : monitor.events()) {
    if (e.kind == "slip" && previous == "stick") return e.time;
    previous = e.kind;
  }
  return -1.0;
}

}  // namespace

nlohmann::ordered_json slip_events(const std::vector<core::SlipHistory>& histories) {
  nlohmann::ordered_json events = nlohmann::ordered_json::object();
  for (const core::SlipHistory& h : histories) {
    nlohmann::ordered_json entry;
    entry["threshold"] = h.monitor.threshold();
    entry["resolution"] = h.monitor.resolution();
    auto time_or_null = [](double t) {
      return t >= 0.0 ? nlohmann::ordered_json(t) : nlohmann::ordered_json(nullptr);
    };
    entry["stick_time"] = time_or_null(h.monitor.stick_time());  // = first_stick, kept
    entry["first_stick"] = time_or_null(h.monitor.stick_time());
    entry["last_stick"] = time_or_null(h.monitor.last_stick());
    entry["first_slip"] = time_or_null(h.monitor.first_slip());
    entry["initial"] = h.monitor.initial_state();
    // A law whose static level is above its kinetic one: its first slip onset from a stick
    // (not a touch-down) is where it broke away at the static level.
    if (h.static_ratio > 1.0) {
      entry["static_ratio"] = h.static_ratio;
      entry["first_breakaway"] = time_or_null(first_breakaway(h.monitor));
    }
    // All events counted, kept or not (SlipMonitor keeps the first and the last ones).
    entry["event_counts"] = {{"stick", h.monitor.count("stick")},
                             {"slip", h.monitor.count("slip")},
                             {"open", h.monitor.count("open")},
                             {"touch_down", h.monitor.touch_downs()}};
    entry["events_total"] = h.monitor.total();
    entry["events_dropped"] = h.monitor.dropped();
    if (h.monitor.dropped() > 0) {
      entry["dropped_from"] = h.monitor.first_dropped();
      entry["dropped_until"] = h.monitor.last_dropped();
    }
    entry["events"] = nlohmann::ordered_json::array();
    std::string previous = h.monitor.initial_state();
    const auto& kept = h.monitor.events();
    for (std::size_t i = 0; i < kept.size(); ++i) {
      const core::SlipEvent& e = kept[i];
      // After the gap the event before is the last dropped one.
      if (h.monitor.dropped() > 0 && i == core::SlipMonitor::kKeptHead)
        previous = h.monitor.last_dropped_kind();
      nlohmann::ordered_json event{{"kind", e.kind}, {"time", e.time}};
      if (previous == "open") event["touch_down"] = true;
      entry["events"].push_back(std::move(event));
      previous = e.kind;
    }
    entry["intervals"] = nlohmann::ordered_json::array();
    for (const core::SlipInterval& i : h.monitor.intervals()) {
      entry["intervals"].push_back(
          {{"kind", i.kind}, {"start", i.start}, {"end", i.end}, {"duration", i.duration()}});
    }
    append_member(events, h.component, std::move(entry));
  }
  return events;
}

nlohmann::ordered_json body_events(const std::vector<core::BodyEventHistory>& bodies) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const core::BodyEventHistory& b : bodies) {
    nlohmann::ordered_json entry;
    entry["points"] = b.points;
    entry["initial"] = b.initial;
    entry["events"] = nlohmann::ordered_json::array();
    for (const core::BodyEvent& e : b.events) {
      entry["events"].push_back({{"kind", e.kind}, {"time", e.time}, {"state", e.state}});
    }
    entry["intervals"] = nlohmann::ordered_json::array();
    for (const core::SlipInterval& i : b.intervals) {
      entry["intervals"].push_back(
          {{"kind", i.kind}, {"start", i.start}, {"end", i.end}, {"duration", i.duration()}});
    }
    append_member(out, b.body, std::move(entry));
  }
  return out;
}

nlohmann::ordered_json column_table(const std::vector<core::ColumnInfo>& columns) {
  nlohmann::ordered_json table = nlohmann::ordered_json::array();
  for (const core::ColumnInfo& c : columns) {
    table.push_back(
        {{"name", c.name}, {"unit", c.unit}, {"frame", c.frame}, {"description", c.description}});
  }
  return table;
}

namespace {

// The state the run ended in (RunResult::end_row), which the output rate may put no row at;
// the last row where a run has no end row. NaN and infinity have no JSON form: nlohmann writes
// them as null. Appended without a key search (io/json_members.hpp); a name met twice keeps
// its first value, checked with a hash set.
nlohmann::ordered_json final_row(const core::RunResult& result) {
  nlohmann::ordered_json row = nlohmann::ordered_json::object();
  const core::Trajectory& tr = result.trajectory;
  const bool has_end = result.end_row.size() == static_cast<std::size_t>(tr.column_count());
  if (!has_end && tr.row_count() == 0) return row;
  const int last = tr.row_count() - 1;
  std::unordered_set<std::string_view> seen;
  for (int c = 0; c < tr.column_count(); ++c) {
    const std::string& name = tr.columns()[static_cast<std::size_t>(c)];
    if (!seen.insert(name).second) continue;
    append_member(row, name,
                  has_end ? result.end_row[static_cast<std::size_t>(c)] : tr.at(last, c));
  }
  return row;
}

}  // namespace

nlohmann::ordered_json make_summary(const RunDescription& run, const core::RunResult& result) {
  nlohmann::ordered_json s;
  s["scene"] = run.scene;
  s["integrator"] = run.integrator;
  s["dt"] = run.dt;
  if (run.tolerance) s["tolerance"] = *run.tolerance;
  s["duration"] = run.duration;
  s["output_rate"] = run.output_rate;
  s["steps"] = result.steps;
  s["evaluations"] = result.evaluations;
  s["state_dim"] = run.state_dim;
  s["wall_seconds"] = result.wall_seconds;
  s["status"] = result.instability ? "unstable" : result.interrupted ? "interrupted" : "ok";
  s["final"] = final_row(result);
  if (!run.columns.empty()) s["columns"] = column_table(run.columns);
  s["events"] = slip_events(result.slip_events);
  std::size_t dropped = 0;
  for (const core::SlipHistory& h : result.slip_events) dropped += h.monitor.dropped();
  s["events_dropped"] = dropped;  // over all elements; each says its own
  s["bodies"] = body_events(result.body_events);
  if (result.instability) {
    nlohmann::ordered_json inst;
    inst["time"] = result.instability->time;
    inst["component"] = result.instability->component;
    inst["reason"] = result.instability->reason;
    if (run.suggested_dt) inst["suggested_dt"] = *run.suggested_dt;
    s["instability"] = std::move(inst);
  }
  return s;
}

void write_summary(const nlohmann::ordered_json& summary, const std::filesystem::path& path) {
  write_file_atomically(path, summary.dump(2) + "\n");
}

}  // namespace stiction::io
