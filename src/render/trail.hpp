// Contact trails: the path of each contact's touching point over the last few seconds, as a
// ribbon lying on its surface, green where the contact sticks and red where it slips. The
// colour uses each contact's own stick threshold (the run's `stick_threshold`, the value the
// slip/stick events use), so the trail and the events always agree.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "render/contact_sites.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

struct TrailOptions {
  double seconds = 0.5;
  // Stick threshold per contact name (m/s); contacts absent here use `default_threshold`.
  std::map<std::string, double> thresholds;
  double default_threshold = 1e-3;
  // Contacts to draw (empty: all of them).
  std::vector<std::string> contacts;
};

// True if the contact's slip speed `slip` (m/s) counts as stuck: below its threshold.
inline bool sticks(double slip, double threshold) { return slip < threshold; }

// One triangle strip holding every chosen contact's ribbon (ribbons joined by degenerate
// triangles). The ribbon of a contact is as wide as a fraction of its body (`trail_width`).
std::vector<TrailVertex> build_trails(const Drawing& scene, const PoseTrack& poses,
                                      double t, const TrailOptions& options);

// Ribbon width for a contact's body: 0.15 radius for a sphere, 0.3 side for a block, 0.15 of
// the smaller of a wheel's radius and length for each of its tracks.
float trail_width(const Drawing& scene, const ContactSite& contact);

}  // namespace stiction::render
