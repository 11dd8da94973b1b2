#include "render/contact_sites.hpp"

namespace stiction::render {

std::map<std::string, double> joint_rate_thresholds(const ContactSites& sites) {
  std::map<std::string, double> out;
  for (const JointSite& j : sites.joints) {
    out[rate_column(j)] = j.stick_threshold;
  }
  return out;
}

SurfacePlane surface_plane(const ContactSite& site, double t) {
  if (site.moving != nullptr) {
    const components::SurfaceState st = site.moving->surface(t);
    return {st.frame.n, st.origin};
  }
  return {site.normal, site.offset * site.normal};
}

namespace {

components::PairProbe probe_at(const ContactSite& site, const PoseTrack& poses, double t) {
  core::BodyMotion a, b;
  a.p = poses.position(site.body, t);
  a.q = poses.orientation(site.body, t);
  b.p = poses.position(site.other, t);
  b.q = poses.orientation(site.other, t);
  return components::probe_pair(site.pair, a, b);
}

}  // namespace

SurfacePlane surface_plane(const ContactSite& site, const PoseTrack& poses, double t) {
  if (site.rule != ContactSite::Rule::pair) return surface_plane(site, t);
  const components::PairProbe probe = probe_at(site, poses, t);
  return {probe.n, probe.point + probe.depth * probe.n};
}

core::Vec3 contact_point(const ContactSite& site, const PoseTrack& poses, double t) {
  if (site.rule == ContactSite::Rule::pair) return probe_at(site, poses, t).point;
  if (site.rule == ContactSite::Rule::rim) {
    // The same point the contact map applies the force at (core/rim_point.hpp).
    return poses.position(site.body, t) +
           site.rim.lever(poses.orientation(site.body, t), site.normal);
  }
  const core::Vec3 centre =
      poses.position(site.body, t) + poses.orientation(site.body, t) * site.local;
  return centre - site.radius * surface_plane(site, t).normal;
}

core::Vec3 carry_with_surface(const components::MovingContact& surface, const core::Vec3& p,
                              double s, double travel_s, double t, double travel_t) {
  const components::SurfaceMotion& motion = surface.motion();
  // The tilt turns the plane about the pivot: x_world = pivot + R (x_rest - pivot).
  core::Vec3 rest = motion.pivot + surface.surface(s).rotation.conjugate() * (p - motion.pivot);
  const core::Vec3 n = surface.params().normal.normalized();
  rest -= (n.dot(rest) - surface.params().offset) * n;  // onto the plane at rest
  rest += (travel_t - travel_s) * surface.belt_direction();
  return motion.pivot + surface.surface(t).rotation * (rest - motion.pivot);
}

}  // namespace stiction::render
