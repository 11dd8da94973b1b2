#include "render/contact_sites.hpp"

#include "components/impedance/kikuuwe_contact.hpp"
#include "components/impedance/pair_contact.hpp"

namespace stiction::render {
namespace {

double threshold_of(const std::map<std::string, double>& thresholds, const std::string& name,
                    double fallback) {
  const auto it = thresholds.find(name);
  return it != thresholds.end() ? it->second : fallback;
}

// The body points of a contact table, in the order the scene builder numbers its elements
// (contact_builder.cpp): the listed `points`, else a box's eight corners, else the origin.
std::vector<core::Vec3> table_points(const toml::table* table, const BodyVisual& body) {
  std::vector<core::Vec3> points;
  if (table != nullptr) {
    if (const toml::array* listed = (*table)["points"].as_array()) {
      for (const toml::node& e : *listed) {
        const toml::array* xyz = e.as_array();
        core::Vec3 v = core::Vec3::Zero();
        for (std::size_t i = 0; xyz != nullptr && i < 3 && i < xyz->size(); ++i) {
          v[static_cast<int>(i)] = (*xyz)[i].value<double>().value_or(0.0);
        }
        points.push_back(v);
      }
      return points;
    }
  }
  if (body.kind == BodyVisual::Kind::box) {
    const core::Vec3 h = 0.5 * body.size;
    for (int i = 0; i < 8; ++i) {
      points.emplace_back((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(),
                          (i & 4 ? 1 : -1) * h.z());
    }
    return points;
  }
  points.emplace_back(core::Vec3::Zero());
  return points;
}

}  // namespace

ContactSites describe_contact_sites(const core::Network& network, const toml::table& document,
                                    const SceneDescription& scene,
                                    const std::map<std::string, double>& thresholds,
                                    double default_threshold) {
  ContactSites sites;
  const toml::table* tables = document["impedances"].as_table();
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance* imp = network.impedances()[i].get();
    const auto wired = network.map_of(static_cast<int>(i)).admittances();
    const int body = wired.empty() ? -1 : body_index(scene, wired.front()->name());
    if (body < 0) continue;
    const BodyVisual& b = scene.bodies[static_cast<std::size_t>(body)];
    const std::string type(imp->type());
    if (type == "kikuuwe_friction" || type == "lugre" || type == "dahl") {
      const toml::table* t = tables ? (*tables)[imp->name()].as_table() : nullptr;
      if (b.kind != BodyVisual::Kind::arm || t == nullptr) continue;
      JointSite j{imp->name(), b.name, body,
                  static_cast<int>((*t)["joint"].value<long>().value_or(0)),
                  threshold_of(thresholds, imp->name(), default_threshold)};
      sites.joints.push_back(j);
      continue;
    }
    if (dynamic_cast<const components::PairContact*>(imp) != nullptr) {
      const auto* map = dynamic_cast<const components::PairContactMap*>(
          &network.map_of(static_cast<int>(i)));
      const int other = wired.size() > 1 ? body_index(scene, wired[1]->name()) : -1;
      if (map == nullptr || other < 0) continue;
      ContactSite s;
      s.name = imp->name();
      const std::size_t dot = s.name.rfind('.');
      const bool table = tables && (*tables)[s.name].as_table();
      s.group = table || dot == std::string::npos ? s.name : s.name.substr(0, dot);
      s.body = body;
      s.other = other;
      s.pair = map->shape();
      s.stick_threshold = threshold_of(thresholds, s.name, default_threshold);
      sites.contacts.push_back(s);
      continue;
    }
    const auto* fixed = dynamic_cast<const components::KikuuweContact*>(imp);
    const auto* moving = dynamic_cast<const components::MovingContact*>(imp);
    if (!fixed && !moving) continue;
    const components::KikuuweContactParams& params = fixed ? fixed->params() : moving->params();
    ContactSite s;
    s.name = imp->name();
    s.group = s.name;
    std::size_t index = 0;
    if (!(tables && (*tables)[s.name].as_table())) {  // element "NAME.i" of table NAME
      const std::size_t dot = s.name.rfind('.');
      s.group = s.name.substr(0, dot);
      index = std::stoul(s.name.substr(dot + 1));
    }
    const toml::table* t = tables ? (*tables)[s.group].as_table() : nullptr;
    const std::vector<core::Vec3> points = table_points(t, b);
    const bool several = s.group != s.name;
    if (index < points.size()) s.local = points[index];
    s.body = body;
    const double default_radius = !several && b.kind == BodyVisual::Kind::sphere ? b.radius : 0.0;
    s.radius = t ? (*t)["radius"].value<double>().value_or(default_radius) : default_radius;
    s.normal = params.normal.normalized();
    s.offset = params.offset;
    s.moving = moving;
    s.stick_threshold = threshold_of(thresholds, s.name, default_threshold);
    sites.contacts.push_back(s);
  }
  return sites;
}

std::map<std::string, double> joint_rate_thresholds(const ContactSites& sites) {
  std::map<std::string, double> out;
  for (const JointSite& j : sites.joints) {
    out[j.arm + ".omega." + std::to_string(j.joint)] = j.stick_threshold;
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
  if (site.other < 0) return surface_plane(site, t);
  const components::PairProbe probe = probe_at(site, poses, t);
  return {probe.n, probe.point + probe.depth * probe.n};
}

core::Vec3 contact_point(const ContactSite& site, const PoseTrack& poses, double t) {
  if (site.other >= 0) return probe_at(site, poses, t).point;
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
