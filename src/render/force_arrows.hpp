// Contact force arrows (normal and friction, two colours) at every contact point and a
// velocity arrow per body, as 3-D draw items (render::add_arrow), with one scale per run:
// N (or m/s) per metre of arrow, given in [overlay] or chosen so that the run's largest
// force (speed) is a readable fraction of the body size; the legend shows a round value.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "render/contact_sites.hpp"
#include "render/overlay_layers_settings.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

// Linear RGB of the arrows (the legend shows them in sRGB).
inline const glm::vec3 kNormalForceColour{0.05f, 0.22f, 0.85f};
inline const glm::vec3 kFrictionColour{0.95f, 0.42f, 0.02f};
// Velocities in charcoal: the force and torque sources' arrows are purple (mechanism_items),
// and a velocity must not read as an applied load.
inline const glm::vec3 kVelocityColour{0.03f, 0.03f, 0.035f};

struct ArrowScales {
  double force = 1.0;           // N per metre of arrow
  double velocity = 1.0;        // (m/s) per metre of arrow
  float shaft_radius = 0.005f;  // metres
  double max_length = 1e30;     // metres: longer arrows are cut to this (impact spikes)
};

// The body size the arrows are measured against: the largest sphere diameter, box side or
// arm link length of the scene (0.1 m without bodies).
double arrow_body_size(const Drawing& scene);

// 1, 2 or 5 times a power of ten, the smallest not below x (x > 0).
double round_up_125(double x);

// The run's scales: the given ones, or the largest normal or friction force over the run
// (the 90th percentile over 129 sample times of the largest at each, so that impact spikes
// do not set it) at 0.6 body sizes and the largest body speed at 0.8 (not rounded: the
// legend shows a round value at this scale). Arrows are cut at 1.5 body sizes.
// `exposure`: a frame's simulated duration, as for contact_force.
ArrowScales choose_arrow_scales(const Drawing& scene, const ContactSites& sites,
                                const PoseTrack& poses, const OverlayLayers& layers,
                                double exposure = 0.0);

// The force on the body at a contact point split along the surface normal at t. With an
// `exposure` (the simulated time a video frame stands for, as the spin blur's), the mean over
// [t - exposure / 2, t + exposure / 2]: a stiff contact that bounces (hundreds of newtons for
// a fraction of a millisecond, nothing in between) shows its mean force, its weight, rather
// than nothing or a spike depending on where the frame falls.
struct ContactForce {
  core::Vec3 normal = core::Vec3::Zero();
  core::Vec3 friction = core::Vec3::Zero();
};
ContactForce contact_force(const ContactSite& site, const PoseTrack& poses, double t,
                           double exposure = 0.0);

// Where a contact's arrows start: the contact point lifted off the surface by the shaft
// radius and moved along the surface towards the camera (`eye`): beside a round body
// (radius > 0), since an arrow up from under a ball would be inside it, and by 1.5 shaft
// radii off a corner, so an arrow along a box's edge is not half inside the box.
core::Vec3 force_arrow_tail(const ContactSite& site, const PoseTrack& poses, double t,
                            const ArrowScales& scales, const glm::vec3& eye);

// The contact force arrows at t as drawn: tail and tip of each (normal, then friction, per
// contact point with a force), cut to the scales' largest length.
struct ArrowSegment {
  core::Vec3 tail, tip;
  bool normal = true;  // the normal force's (else friction's)
};
std::vector<ArrowSegment> force_arrow_segments(const ContactSites& sites, const PoseTrack& poses,
                                               double t, const ArrowScales& scales,
                                               const glm::vec3& eye, double exposure = 0.0);

// Normal and friction arrows of every contact point (a zero force adds nothing).
void add_force_arrows(std::vector<DrawItem>& items, const ContactSites& sites,
                      const PoseTrack& poses, double t, const ArrowScales& scales,
                      const glm::vec3& eye, double exposure = 0.0);

// One arrow per body with a velocity (`<b>.v.*`), from the body's surface along v.
void add_velocity_arrows(std::vector<DrawItem>& items, const Drawing& scene, const PoseTrack& poses,
                         double t, const ArrowScales& scales);

}  // namespace stiction::render
