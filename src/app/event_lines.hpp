// The lines `stiction run` prints about events (from summary.json, so the terminal and the
// file say the same): one per element with a slip speed (its first stick and first slip, or
// that it sticks or slides throughout) and one per body with several contact points (its
// body-level events: tips, slides, sticks, lifts off, lands). Every time is printed with
// text::kEventTimeDigits significant digits (text/number_text.hpp), stick and slip alike.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace stiction::app {

// One line per element, without a trailing newline, e.g.
// "ground: first stick at t = 0.5843614 s, first slip at t = 0.0001 s (starts open; 56
// sticks, 57 slips, 3 touch-downs)", "floor.0: sticks throughout (starts stick; 0 sticks,
// 0 slips, 1 lift-off)", "belt: slides throughout (...)".
// With summary.json's `accuracy` holding an estimate of an event's error, the time gets its
// error bar: "first stick at t = 1.483965 s (+- 2e-07 s)".
std::vector<std::string> event_lines(const nlohmann::ordered_json& events,
                                     const nlohmann::ordered_json& accuracy = {});

// One line per body of summary.json's `bodies`, e.g. "box: starts sticking, tips at
// t = 1.6333 s" or "box: sticks throughout"; at most kBodyEventsPrinted events, then how many
// more the summary lists.
inline constexpr int kBodyEventsPrinted = 8;
std::vector<std::string> body_event_lines(const nlohmann::ordered_json& bodies);

}  // namespace stiction::app
