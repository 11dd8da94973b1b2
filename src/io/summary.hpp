// summary.json (DESIGN section 4): what was run, how it ended, the last row by column name
// and the stick/slip events of every contact and of every body with several contact points.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/column_info.hpp"
#include "core/simulation.hpp"

namespace stiction::io {

struct RunDescription {
  std::string scene;
  std::string integrator;
  double dt = 0.0;
  double duration = 0.0;
  double output_rate = 0.0;
  int state_dim = 0;
  std::optional<double> tolerance;          // rk4_adaptive only
  std::optional<double> suggested_dt;       // reported with an instability
  std::vector<core::ColumnInfo> columns{};  // `columns`: one per CSV column, t first
};

// {"<contact>": {"threshold": ..., "resolution": ..., "stick_time": first stick or null
//                (compatibility; = first_stick), "first_stick", "last_stick", "first_slip"
//                (each a time or null), "initial": state at t = 0,
//                "events": [{"kind": "stick"|"slip"|"open", "time": ...,
//                            "touch_down": true after an "open"}, ...],
//                "intervals": [{"kind", "start", "end", "duration"}, ...]}}
nlohmann::ordered_json slip_events(const std::vector<core::SlipHistory>& histories);

// {"<body>": {"points": [its contact elements], "initial": state at t = 0,
//             "events": [{"kind": "stick"|"slide"|"partial_slip"|"tip"|"lift_off"|"land",
//                         "time": ..., "state": the state entered}, ...],
//             "intervals": [{"kind", "start", "end", "duration"}, ...]}}
// for every body with several contact points (core/body_events.hpp, docs/events.md).
nlohmann::ordered_json body_events(const std::vector<core::BodyEventHistory>& bodies);

// [{"name", "unit", "frame", "description"}, ...] in CSV column order.
nlohmann::ordered_json column_table(const std::vector<core::ColumnInfo>& columns);

nlohmann::ordered_json make_summary(const RunDescription& run, const core::RunResult& result);

// Written atomically, indented; IoError on failure.
void write_summary(const nlohmann::ordered_json& summary, const std::filesystem::path& path);

}  // namespace stiction::io
