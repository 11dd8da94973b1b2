// Time-warp: frame times that slow the video down around events (a contact starting to
// stick or to slip), so a transition that lasts a few milliseconds of a long run gets
// screen time. Within `window` simulated seconds of an event the video plays `factor` times
// slower than elsewhere; over the next half window the speed ramps back linearly.
#pragma once

#include <string>
#include <vector>

namespace stiction::render {

struct FrameTime {
  double t = 0.0;      // simulated time shown
  double speed = 1.0;  // playback speed relative to the run's slow_motion (1/factor: slowest)
};

// Frames every `step` simulated seconds from `start` through `end` (both ends included when
// `end - start` is a whole number of steps), the step scaled by the speed near `events`.
// window <= 0 or no events: uniform frames.
std::vector<FrameTime> warped_frame_times(double start, double end, double step,
                                          const std::vector<double>& events, double window,
                                          double factor);

// The events of the first `episodes` episodes, in time order: events less than two windows
// apart (whose slowed stretches would touch) are one episode. episodes <= 0: all.
std::vector<double> first_episodes(std::vector<double> events, double window, int episodes);

// The events the video slows down around ([render] slowed_events = `episodes`): with
// episodes <= 0 every event, as given; else the changes between slip and stick only (a
// contact's "open" / touch-down chatter and a kind repeating are left out, as the inset
// marks them: sphere_roll's micro-bounces would chain the whole run into one episode), of
// the first `episodes` episodes. `kinds` parallel to `times` (empty: every event counts).
std::vector<double> slowed_events(const std::vector<double>& times,
                                  const std::vector<std::string>& kinds, double window,
                                  int episodes);

// Playback speed at time t (1 far from events, 1/factor within `window` of one).
double playback_speed(double t, const std::vector<double>& events, double window, double factor);

}  // namespace stiction::render
