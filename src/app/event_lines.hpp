// The lines `stiction run` prints about the events of each element with a slip speed: its
// first stick and first slip, or that it never sticks or never slips (from summary.json's
// `events`, so the terminal and the file say the same).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace stiction::app {

// One line per element, without a trailing newline, e.g.
// "ground: first stick at t = 0.58436 s, never slips (starts open; 3 touch-downs)".
// With summary.json's `accuracy` holding an estimate of an event's error, the time gets its
// error bar: "first stick at t = 1.483965 s (+- 2e-07 s)".
std::vector<std::string> event_lines(const nlohmann::ordered_json& events,
                                     const nlohmann::ordered_json& accuracy = {});

}  // namespace stiction::app
