#include "services/plot_outputs.hpp"

#include "sys/interrupt.hpp"

namespace stiction::services {

std::vector<plot::PlotEvent> plot_events(const core::RunResult& result) {
  std::vector<plot::PlotEvent> events;
  for (const core::SlipHistory& h : result.slip_events) {
    for (const core::SlipEvent& e : h.monitor.events())
      events.push_back({h.component, e.kind, e.time});
  }
  return events;
}

std::vector<std::filesystem::path> write_run_plots(const std::vector<plot::PlotSpec>& specs,
                                                   const core::RunResult& result,
                                                   const core::Trajectory& rows,
                                                   const std::filesystem::path& dir,
                                                   std::optional<plot::Format> format) {
  const std::vector<plot::PlotEvent> events = plot_events(result);
  std::vector<std::filesystem::path> written;
  for (const plot::PlotSpec& spec : specs) {
    if (sys::interrupted()) break;  // the run reports the plots written so far
    const std::filesystem::path path = plot::plot_path(spec, dir, format);
    plot::write_plot(spec, rows, events, path,
                     format.value_or(spec.format.value_or(plot::Format::png)));
    written.push_back(path);
  }
  return written;
}

}  // namespace stiction::services
