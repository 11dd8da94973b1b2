#include "services/plot_outputs.hpp"

#include "sys/interrupt.hpp"

namespace stiction::services {

std::vector<plot::PlotEvent> plot_events(const core::RunResult& result) {
  std::vector<plot::PlotEvent> events;
  for (const core::SlipHistory& h : result.slip_events) {
    // Lift-offs ("open") go along: the stick or slip after one is a touch-down, a tick on the
    // figures. An element that starts in the air touches down at its first event.
    bool airborne = h.monitor.initial_state() == "open";
    for (const core::SlipEvent& e : h.monitor.events()) {
      plot::PlotEvent event{h.component, e.kind, e.time};
      event.touch_down = airborne && e.kind != "open";
      event.body = h.body;
      airborne = false;
      events.push_back(event);
    }
  }
  // A body with several contact points: its own events (a tip, a slide) tell its story, and
  // its points' events become ticks (event_selection.hpp).
  for (const core::BodyEventHistory& body : result.body_events) {
    for (const core::BodyEvent& e : body.events) {
      plot::PlotEvent event{body.body, e.kind, e.time};
      event.body_level = true;
      events.push_back(event);
    }
  }
  return events;
}

plot::Figure run_figure(const plot::PlotSpec& spec, const core::RunResult& result,
                        const core::Trajectory& rows) {
  return plot::make_figure(spec, rows, plot_events(result));
}

std::vector<std::filesystem::path> write_run_plots(const std::vector<plot::PlotSpec>& specs,
                                                   const core::RunResult& result,
                                                   const core::Trajectory& rows,
                                                   const std::filesystem::path& dir,
                                                   std::optional<plot::Format> format) {
  std::vector<std::filesystem::path> written;
  for (const plot::PlotSpec& spec : specs) {
    if (sys::interrupted()) break;  // the run reports the plots written so far
    const std::filesystem::path path = plot::plot_path(spec, dir, format);
    plot::write_figure(run_figure(spec, result, rows), path,
                       format.value_or(spec.format.value_or(plot::Format::png)), spec.dpi);
    written.push_back(path);
  }
  return written;
}

}  // namespace stiction::services
