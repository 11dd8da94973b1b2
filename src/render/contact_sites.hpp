// Where forces act and regimes are judged, for the overlay layers of issue 22 (force arrows,
// stick/slip/open badges): every contact point (one per element "NAME" or "NAME.i" of a
// kikuuwe_contact table, box corners and listed points included) and every friction joint of
// a planar arm, with the stick threshold its events use. Built from the network and the
// document (scene_view's ContactVisual keeps only single-point contacts).
#pragma once

#include <toml++/toml.h>

#include <map>
#include <string>
#include <vector>

#include "components/impedance/moving_contact.hpp"
#include "components/maps/pair_contact_map.hpp"
#include "core/network.hpp"
#include "core/types.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {

struct ContactSite {
  std::string name;   // element name: its columns are NAME.f.*, NAME.slip.*, NAME.n_force
  std::string group;  // the contact table ("floor" for "floor.3")
  int body = -1;      // index into SceneDescription::bodies
  core::Vec3 local = core::Vec3::Zero();  // body-frame point the contact sits about
  double radius = 0.0;                    // round shape about `local` (a sphere's radius)
  core::Vec3 normal{0.0, 0.0, 1.0};       // surface normal at rest (unit)
  double offset = 0.0;                    // surface plane n . x = offset at rest
  const components::MovingContact* moving = nullptr;  // null: fixed surface
  double stick_threshold = 1e-3;                      // m/s
  // A contact between two bodies (`other`): the second body's index and the pair's shape;
  // its normal and point come from both poses (probe_pair), not from a plane.
  int other = -1;
  components::PairShape pair{};
};

// A friction element on a planar arm's joint: its slip speed is |ARM.omega.JOINT|.
struct JointSite {
  std::string name;  // the friction element (its column NAME.tau)
  std::string arm;   // the arm's name: its columns ARM.omega.JOINT
  int body = -1;     // the arm's index into SceneDescription::bodies
  int joint = 0;
  double stick_threshold = 1e-3;  // rad/s
};

struct ContactSites {
  std::vector<ContactSite> contacts;
  std::vector<JointSite> joints;
};

// The contact and joint sites of a built scene. `thresholds`: the run's stick threshold per
// element (scene.run.stick_thresholds), `default_threshold` for the others.
ContactSites describe_contact_sites(const core::Network& network, const toml::table& document,
                                    const SceneDescription& scene,
                                    const std::map<std::string, double>& thresholds,
                                    double default_threshold);

// "ARM.omega.J" -> the stick threshold of the friction joint J of ARM (for the overlay's
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

// The contact point at time t: the body point minus radius times the surface normal.
core::Vec3 contact_point(const ContactSite& site, const PoseTrack& poses, double t);

// The world point where the material point of a moving surface that was at `p` at time `s`
// is at time `t` (tilted with the plane, carried by the belt), projected onto the plane at
// t. `travel_s`, `travel_t`: the belt's travel at s and t (MovingContact::belt_travel).
core::Vec3 carry_with_surface(const components::MovingContact& surface, const core::Vec3& p,
                              double s, double travel_s, double t, double travel_t);

}  // namespace stiction::render
