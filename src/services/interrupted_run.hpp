// What `run` does when SIGINT or SIGTERM arrived (sys/interrupt.hpp): summary.json says
// "interrupted", with the phase and the simulated time reached, and the command exits 130
// or 143 after saying on stderr what it kept.
#pragma once

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "sys/interrupt.hpp"

namespace stiction::services {

inline void mark_interrupted(nlohmann::ordered_json& summary, const char* phase, double time_reached) {
  summary["status"] = "interrupted";
  summary["interrupted"] = {{"signal", sys::interrupt_signal_name()},
                            {"phase", phase},
                            {"time_reached", time_reached}};
}

// The message and the exit code (128 + signal). `files` lists what was kept.
inline int interrupted_exit(bool quiet, const char* phase, const nlohmann::ordered_json& files,
                            double time_reached = 0.0) {
  if (!quiet) {
    std::fprintf(stderr, "interrupted by %s during %s", sys::interrupt_signal_name(), phase);
    if (files.empty()) {
      std::fprintf(stderr, "; nothing written\n");
    } else {
      std::fprintf(stderr, " at t = %g s; kept as partial: %s\n", time_reached,
                   files.dump().c_str());
    }
  }
  return sys::interrupt_exit_code();
}

// The name render_outputs gives frame i.
inline std::string frame_name(int i) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", i);
  return name;
}

}  // namespace stiction::services
