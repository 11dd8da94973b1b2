// The study's reports: study.csv (one row per run), study.md (tables a user can paste) and
// work_precision.png (error against cost, log-log).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "services/study.hpp"
#include "image/png.hpp"
#include "io/atomic_file.hpp"
#include "plot/figure.hpp"
#include "plot/plot_spec.hpp"
#include "text/number_text.hpp"

namespace stiction::services {
namespace {

std::string num(double value, int digits = 4) {
  if (!std::isfinite(value)) return "";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

// A value the reader may give back (a step, a tolerance, the scene's settings): shortest
// round-trip (text/number_text.hpp), not rounded to digits that would not reproduce it.
std::string value(double v) { return std::isfinite(v) ? text::shortest(v) : ""; }

// For Markdown cells: a dash where there is no value.
std::string cell(double value, int digits = 3) {
  const std::string s = num(value, digits);
  return s.empty() ? "–" : s;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

double max_event_error(const StudyRow& row) {
  double worst = row.event_errors.empty() ? NAN : 0.0;
  for (double e : row.event_errors) {
    if (!(e <= worst)) worst = e;
  }
  return worst;
}

// An infinite error (a missed event) is "inf", not an empty field: empty means "not measured".
std::string error_field(double value) {
  return std::isinf(value) ? std::string("inf") : num(value, 6);
}

// For Markdown cells: "missed" for an infinite event error.
std::string error_cell(double value) {
  return std::isinf(value) ? std::string("missed") : cell(value);
}

std::string step_cell(const StudyRow& row) {
  return row.tolerance > 0.0 ? "tol " + value(row.tolerance) : value(row.dt);
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += separator;
    out += item;
  }
  return out;
}

const Recommendation* candidate_of(const StudyResult& r, const std::string& integrator) {
  for (const auto& c : r.candidates) {
    if (c.integrator == integrator) return &c;
  }
  return nullptr;
}

// The two largest steps of each integrator side by side.
std::string largest_steps_markdown(const StudyResult& r) {
  std::string md;
  if (!r.limits.empty()) {
    md +=
        "\n## Largest step: by stability and by accuracy\n\n"
        "Predicted (as `stiction check`): stuck friction chatters above the first figure, the "
        "run blows up above the second. Largest stable: the bisected stability limit above. "
        "Largest within the target: the largest step whose run meets the target with every "
        "step tried below it meeting it too, bisected to 1% between the grid's steps; the next "
        "column says what breaks the target just above it. Cost: of the cheapest run within "
        "the target (the run at that step), network evaluations and CPU seconds (median of "
        "the timing runs) per simulated second.\n\n";
    md +=
        "| integrator | chatters above [s] | unstable above [s] | largest stable [s] | largest "
        "within target [s] | above it | evaluations / s | CPU s / s | runs | grid steps past "
        "the limit |\n|---|---:|---:|---:|---:|---|---:|---:|---:|---:|\n";
    for (const auto& l : r.limits) {
      const std::string predicted =
          l.predicted_skipped     ? std::string("skipped")
          : l.predicted_unbounded ? ">= " + num(l.predicted, 4)
                                  : cell(l.predicted, 4);
      std::string above = l.accuracy_failure.empty()
                              ? std::string("–")
                              : l.accuracy_failure + " at " + num(l.inaccurate_above, 4) + " s";
      if (!l.accuracy_note.empty()) above += " (" + l.accuracy_note + ")";
      const bool accurate = l.accurate > 0.0;
      const Recommendation* c = candidate_of(r, l.integrator);
      md += "| " + l.integrator + " | " + cell(l.chatter_free, 4) + " | " + predicted + " | " +
            cell(l.bisected > 0.0 ? l.bisected : NAN, 4) + " | " +
            cell(accurate ? l.accurate : NAN, 4) + " | " + above + " | " +
            cell(c != nullptr ? c->evaluations_per_second : NAN, 4) + " | " +
            cell(c != nullptr ? c->cpu_per_second : NAN, 3) + " | " +
            std::to_string(l.runs + l.accuracy_runs) + " | " + std::to_string(l.grid_past_limit) +
            " |\n";
    }
  }
  for (const auto& row : r.rows) {
    if (row.tolerance > 0.0) {
      const double tol = largest_accurate_tolerance(r, row.integrator);
      const Recommendation* c = candidate_of(r, row.integrator);
      md += "\n" + row.integrator + ": largest tolerance within the target " +
            (tol > 0.0 ? value(tol) : std::string("none (no tolerance tried meets it)"));
      if (c != nullptr) {
        md += " (with every tighter one); its cheapest run within the target, tolerance " +
              value(c->tolerance) + ": " + num(c->evaluations_per_second, 4) +
              " evaluations and " + num(c->cpu_per_second, 3) + " CPU s per simulated second";
      }
      md += ".\n";
      break;
    }
  }
  return md;
}

// The closing line: the cheapest run within the target.
std::string recommendation_line(const StudyResult& r) {
  const Recommendation& rec = r.recommendation;
  std::string md = "\n**Recommendation** (target " + value(r.target_error) + "): ";
  if (rec.integrator.empty()) {
    md +=
        "no run meets the target; try a smaller `--dts` or `--tolerances`, or a larger "
        "`--target-error`.\n";
    return md;
  }
  md += "`" + rec.integrator + "` at " +
        (rec.tolerance > 0.0 ? "tolerance " + value(rec.tolerance)
                             : "dt = " + value(rec.dt) + " s") +
        ", " + num(rec.cpu_per_second, 3) + " CPU s (median of " + std::to_string(rec.repeats) +
        ") and " + num(rec.evaluations_per_second, 4) + " network evaluations per simulated second";
  std::vector<std::string> errors;
  if (std::isfinite(rec.event_time_error))
    errors.push_back("event times " + num(rec.event_time_error, 2));
  if (std::isfinite(rec.final_value_error))
    errors.push_back("final values " + num(rec.final_value_error, 2));
  if (!errors.empty()) md += " (errors: " + join(errors, ", ") + ")";
  md += rec.bisected ? "; a step the accuracy bisection ran, not a grid row" : "";
  if (!rec.note.empty()) md += "; " + rec.note;
  md += ". The least CPU time among each integrator's cheapest run within the target";
  md += rec.run_verdict == "accurate"
            ? ", and `stiction run` at this setting calls itself accurate.\n"
            : ". `stiction run` at this setting says `" + rec.run_verdict + "` (docs/accuracy.md).\n";
  return md;
}

}  // namespace

std::string study_csv(const StudyResult& r) {
  std::string out = "integrator,dt,tolerance,status,unstable_time,unstable_component,steps,"
                    "evaluations,wall_seconds,repeats,key_error,worst_signal";
  for (const auto& s : r.key_signals) out += ",error_" + s;
  for (const auto& name : r.event_names) {
    // "ground stick" -> stick_time_ground, stick_error_ground, stick_relative_error_ground
    const std::size_t space = name.rfind(' ');
    const std::string element = name.substr(0, space), kind = name.substr(space + 1);
    out += ',' + csv_field(kind + "_time_" + element);
    out += ',' + csv_field(kind + "_error_" + element);
    out += ',' + csv_field(kind + "_relative_error_" + element);
  }
  // Added after the per-signal and per-event columns: readers that take the columns above by
  // position keep working.
  out += ",cpu_seconds,event_time_error,final_value_error,meets_target,accuracy_failure";
  out += '\n';
  for (const auto& row : r.rows) {
    out += csv_field(row.integrator);
    out += ',' + value(row.dt) + ',' + (row.tolerance > 0.0 ? value(row.tolerance) : "");
    out += ',' + row.status;
    out += ',' + (row.instability ? num(row.instability->time, 10) : std::string());
    out += ',' + (row.instability ? csv_field(row.instability->component) : std::string());
    out += ',' + std::to_string(row.steps) + ',' + std::to_string(row.evaluations);
    out += ',' + num(row.wall_seconds, 6) + ',' + std::to_string(row.repeats);
    out += ',' + num(row.key_error, 6) + ',' + csv_field(row.worst_signal);
    for (double e : row.signal_errors) out += ',' + num(e, 6);
    for (std::size_t i = 0; i < r.event_names.size(); ++i) {
      out += ',' + num(row.event_times[i], 10);
      out += ',' + num(row.event_errors[i], 6);
      out += ',' + num(row.event_relative_errors[i], 6);
    }
    out += ',' + num(row.cpu_seconds, 6);
    out += ',' + error_field(row.event_time_error) + ',' + error_field(row.final_value_error);
    out += ',' + std::string(row.meets_target ? "1" : "0");
    out += ',' + csv_field(row.accuracy_failure);
    out += '\n';
  }
  return out;
}

std::string study_markdown(const StudyResult& r) {
  std::string md = "# `stiction study " + r.scene + "`\n\n";
  md += "Scene dt " + value(r.scene_dt) + " s, duration " + value(r.duration) + " s, output " +
        value(r.output_rate) + " rows/s. ";
  md += "Reference: **" + r.reference_integrator + " at dt = " + value(r.reference_dt) + " s** (" +
        num(r.scene_dt / r.reference_dt, 3) + "x finer than the scene's), " +
        std::to_string(r.reference_steps) + " steps, " + num(r.reference_wall_seconds, 3) +
        " s. rk4 at twice that step differs from it by " + cell(r.reference_noise, 3) + " (key error)" +
        (r.event_names.empty() ? std::string() : " and " + cell(r.reference_event_noise, 3) + " (event times, relative)") +
        ": errors near these measure the reference as much as the run.\n\n";
  md += "Key error: max over the key signals (" + join(r.key_signals, ", ") +
        ") of max |x - x_ref| over the common output rows (for a fixed step, the rows that fall on one "
        "of its steps: the others are interpolated linearly between steps), divided by the signal's "
        "scale (the largest |value| of its vector in the reference). ";
  if (!r.event_names.empty()) {
    md += "Event error: the first stick and the first slip of each contact/joint, those the "
          "reference has, against the reference's (";
    std::vector<std::string> refs;
    for (std::size_t i = 0; i < r.event_names.size(); ++i) {
      refs.push_back(r.event_names[i] + " " + cell(r.reference_event_times[i], 7) + " s");
    }
    md += join(refs, ", ") + "); the worst of them, absolute and relative to the reference time "
          "(each one in the table \"Event errors\" below). ";
  } else if (!r.slip_components.empty()) {
    md += "Event error: none measured, the reference has no stick and no slip event. ";
  }
  md += "Wall time: the simulation alone, median of the repeats (rep).\n\n";
  md += "Accuracy target " + value(r.target_error) +
        " (`--target-error`): a run meets it when every " +
        (r.event_names.empty()
             ? std::string()
             : "event time (error divided by the duration, " + value(r.duration) + " s) and every ") +
        "final value of a key signal (error divided by the signal's scale) is within it of the "
        "reference's. The reference's own such error (rk4 at twice its step) is " +
        cell(r.reference_accuracy_noise, 3) + ".\n\n";

  md +=
      "| integrator | dt [s] | status | steps | evaluations | wall [ms] | rep | key error | worst "
      "signal "
      "| event error [s] | event error (rel) | event time error (/ duration) | final value error | "
      "within target |\n";
  md += "|---|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---|\n";
  for (const auto& row : r.rows) {
    std::string status = row.status;
    if (row.instability) {
      status += " at " + num(row.instability->time, 4) + " s (" + row.instability->component + ")";
    }
    md += "| " + row.integrator + " | " + step_cell(row) + " | " + status + " | " +
          std::to_string(row.steps) + " | " + std::to_string(row.evaluations) + " | " +
          cell(1e3 * row.wall_seconds, 3) + " | " + std::to_string(row.repeats) + " | " +
          cell(row.key_error) + " | " + (row.worst_signal.empty() ? "–" : row.worst_signal) +
          " | " + cell(max_event_error(row)) + " | " + cell(row.max_event_relative_error) + " | " +
          error_cell(row.event_time_error) + " | " + error_cell(row.final_value_error) + " | " +
          (row.meets_target ? std::string("yes") : "no (" + row.accuracy_failure + ")") + " |\n";
  }

  if (!r.event_names.empty()) {
    md += "\n## Event errors\n\nEach event's time and its error relative to the reference's "
          "time (– where the run has no such event).\n\n| integrator | dt [s] |";
    std::string rule = "|---|---:|";
    for (const auto& name : r.event_names) {
      md += ' ';
      md += name;
      md += " [s] | ";
      md += name;
      md += " (rel) |";
      rule += "---:|---:|";
    }
    md += '\n';
    md += rule;
    md += '\n';
    for (const auto& row : r.rows) {
      md += "| " + row.integrator + " | " + step_cell(row) + " |";
      for (std::size_t i = 0; i < r.event_names.size(); ++i) {
        md += ' ';
        md += cell(row.event_times[i], 7);
        md += " | ";
        md += cell(row.event_relative_errors[i]);
        md += " |";
      }
      md += "\n";
    }
  }

  if (!r.orders.empty()) {
    md += "\n## Observed order\n\nSlope of log(key error) against log(dt) over the stable rows "
          "whose key error lies between 10x the reference's noise and 0.05 (saturated); – when "
          "fewer than two rows qualify.\n\n";
    md += "| integrator | observed order | rows used | dt range [s] |\n|---|---:|---:|---|\n";
    for (const auto& o : r.orders) {
      md += "| " + o.integrator + " | " + cell(o.order, 3) + " | " + std::to_string(o.points) + " | " +
            (o.points > 0 ? num(o.dt_min, 3) + " – " + num(o.dt_max, 3) : "–") + " |\n";
    }
  }

  if (!r.limits.empty()) {
    md += "\n## Stability limits\n\nPredicted: `core::predict_step_limit`, spectral radius of "
          "the step map linearized at states sampled along a run at the scene's own options "
          "(every regime the run passes through), each element held in its regime. "
          "Chatter-free: below this step no stuck friction spring oscillates either; between "
          "it and the predicted limit such an oscillation is bounded by the friction limit "
          "and too small for the energy monitor. Bisected: whole runs of the scene (its full "
          "duration), unstable when the run's monitor stops it (non-finite state or energy "
          "growth); the largest stable step found, the bracket closed to 1%.\n\n";
    md += "| integrator | predicted [s] | limiting state t [s] | chatter-free [s] | bisected [s] "
          "| first unstable [s] | predicted / bisected | runs | note |\n"
          "|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const auto& l : r.limits) {
      const std::string predicted = l.predicted_skipped     ? std::string("skipped")
                                    : l.predicted_unbounded ? ">= " + num(l.predicted, 4)
                                                            : cell(l.predicted, 4);
      const double ratio = l.bisected > 0.0 && l.predicted > 0.0 ? l.predicted / l.bisected : NAN;
      md += "| " + l.integrator + " | " + predicted + " | " + cell(l.predicted_time, 4) + " | " +
            cell(l.chatter_free, 4) + " | " + cell(l.bisected > 0.0 ? l.bisected : NAN, 4) + " | " +
            cell(l.unstable_above > 0.0 ? l.unstable_above : NAN, 4) + " | " + cell(ratio, 3) +
            " | " + std::to_string(l.runs) + " | " + (l.note.empty() ? std::string("–") : l.note) +
            " |\n";
    }
  }
  md += largest_steps_markdown(r);
  if (!r.notes.empty()) {
    md += "\n## Notes\n\n";
    for (const auto& n : r.notes) md += "- " + n + "\n";
  }
  md += "\nWhole study: " + num(r.total_seconds, 3) + " s.\n";
  md += recommendation_line(r);
  return md;
}

image::Image work_precision_figure(const StudyResult& r, text::Font& font) {
  return plot::render(work_precision_plot(r), font);
}

plot::Figure work_precision_plot(const StudyResult& r) {
  plot::Figure figure;
  figure.panels.reserve(2);  // `key` and `events` point into it
  figure.title = "Work-precision: " + r.scene + " (reference rk4, dt = " + value(r.reference_dt) + " s)";
  // The figure's horizontal axis is linear only: it carries log10 of the cost.
  figure.x_label = "Cost: log\u2081\u2080(wall time of the simulation / 1 s)";
  figure.x_unit = "";
  plot::Panel& key = figure.panels.emplace_back();
  key.label = "Key-signal error (relative)";
  key.log = true;
  plot::Panel* events = nullptr;
  if (!r.event_names.empty()) {
    events = &figure.panels.emplace_back();
    events->label = "Event-time error (relative, worst)";
    events->log = true;
    events->references.push_back({1e-4, "1e-4"});
  }
  // Keep the order of first appearance of the integrators.
  std::vector<std::string> integrators;
  for (const auto& row : r.rows) {
    if (std::find(integrators.begin(), integrators.end(), row.integrator) == integrators.end()) {
      integrators.push_back(row.integrator);
    }
  }
  for (std::size_t k = 0; k < integrators.size(); ++k) {
    std::vector<const StudyRow*> rows;
    for (const auto& row : r.rows) {
      if (row.integrator == integrators[k] && row.status == "ok" && row.wall_seconds > 0.0) rows.push_back(&row);
    }
    std::sort(rows.begin(), rows.end(),
              [](const StudyRow* a, const StudyRow* b) { return a->wall_seconds < b->wall_seconds; });
    plot::Series ks, ss;
    ks.label = integrators[k];  // one legend (top panel) serves both panels
    ks.style = ss.style = plot::series_style(static_cast<int>(k));
    for (const StudyRow* row : rows) {
      const double x = std::log10(row->wall_seconds);
      ks.x.push_back(x);
      ks.y.push_back(row->key_error > 0.0 ? row->key_error : NAN);
      ss.x.push_back(x);
      ss.y.push_back(row->max_event_relative_error > 0.0 ? row->max_event_relative_error : NAN);
    }
    key.series.push_back(std::move(ks));
    if (events != nullptr) events->series.push_back(std::move(ss));
  }
  // The print size of every figure: one journal column, its height by the panel count.
  const plot::PrintSize print;
  figure.print = plot::Figure::Print{print.width_mm, plot::default_height_mm(figure.panels.size()),
                                     print.font_pt, 300.0};
  return figure;
}

void write_study(const StudyResult& result, const std::filesystem::path& out) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw io::IoError(out.string() + ": cannot create the output directory: " + ec.message());
  io::write_file_atomically(out / "study.csv", study_csv(result));
  io::write_file_atomically(out / "study.md", study_markdown(result));
  text::Font font = text::Font::open_default();
  image::write_png(out / "work_precision.png", work_precision_figure(result, font), image::PngSpeed::small);
}

}  // namespace stiction::services
