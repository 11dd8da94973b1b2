// Where forces act and regimes are judged, for the overlay layers of issue 22 (force arrows,
// stick/slip/open badges, contact dots) and the trails: the contact sites the scene declares
// (scene/drawing.hpp, Drawing::sites), placed at time t from the poses in the signals. A
// sphere's contact sits at its lowest point, a box's at its corners, a cylinder's or ring's
// on its rim nearest the surface, a pair's where the two shapes meet.
#pragma once

#include <map>
#include <string>

#include "core/types.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

using scene::ContactSite;
using scene::ContactSites;
using scene::JointSite;

// "ARM.omega.J" (rate_column) -> the stick threshold of the friction joint J of ARM (for the overlay's
// values: a stuck joint's rate prints as zero).
std::map<std::string, double> joint_rate_thresholds(const ContactSites& sites);

// The surface plane at time t: unit normal and a point of it.
struct SurfacePlane {
  core::Vec3 normal;
  core::Vec3 origin;
};
SurfacePlane surface_plane(const ContactSite& site, double t);
// The same for any site: a pair contact's normal at the contact point (pushing `body`), with
// origin such that the gap is minus the penetration.
SurfacePlane surface_plane(const ContactSite& site, const PoseTrack& poses, double t);

// The contact point at time t: the body point minus radius times the surface normal; a rim
// site's rim point nearest the surface; a pair's point between the two shapes.
core::Vec3 contact_point(const ContactSite& site, const PoseTrack& poses, double t);

// The world point where the material point of a moving surface that was at `p` at time `s`
// is at time `t` (tilted with the plane, carried by the belt), projected onto the plane at
// t. `travel_s`, `travel_t`: the belt's travel at s and t (MovingContact::belt_travel).
core::Vec3 carry_with_surface(const components::MovingContact& surface, const core::Vec3& p,
                              double s, double travel_s, double t, double travel_t);

}  // namespace stiction::render
