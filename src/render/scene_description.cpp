// describe_scene: what to draw, from the network's components and the scene document.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "components/admittance/planar_arm.hpp"
#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/admittance/spatial_tree.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "components/impedance/moving_contact.hpp"
#include "components/impedance/penalty_joint.hpp"
#include "core/admittance.hpp"
#include "core/coordinate_map.hpp"
#include "render/mechanism_description.hpp"
#include "render/scene_view.hpp"

namespace stiction::render {
namespace {

const toml::table* body_table(const toml::table& document, const std::string& name) {
  const toml::table* bodies = document["bodies"].as_table();
  return bodies ? (*bodies)[name].as_table() : nullptr;
}

core::Vec3 vec3_of(const toml::node_view<const toml::node>& node, const core::Vec3& fallback) {
  const toml::array* a = node.as_array();
  if (!a || a->size() != 3) return fallback;
  core::Vec3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = (*a)[static_cast<std::size_t>(i)].value<double>().value_or(fallback[i]);
  return v;
}

// A cylinder's visual: radius, length, body-frame axis, and the body-frame box around it
// (what the box-like parts of framing and bounds use).
void describe_cylinder(const toml::table& table, BodyVisual& b) {
  b.kind = BodyVisual::Kind::cylinder;
  b.radius = table["radius"].value<double>().value_or(0.1);
  b.length = table["length"].value<double>().value_or(0.1);
  b.hollow = table["hollow"].value<bool>().value_or(false);
  b.axis = vec3_of(table["axis"], core::Vec3::UnitZ()).normalized();
  for (int i = 0; i < 3; ++i) {
    const double a = std::abs(b.axis[i]);
    b.size[i] = b.length * a + 2.0 * b.radius * std::sqrt(std::max(0.0, 1.0 - a * a));
  }
}

// A tree's links: each one's reach (the farthest of its children's joints and its centre
// of mass, at least 2 cm) and a thickness a tenth of it, for the stick figure and framing.
void describe_tree(BodyVisual& b, const components::SpatialTree& tree) {
  b.kind = BodyVisual::Kind::tree;
  b.tree = &tree;
  const auto& links = tree.params().links;
  b.lengths.assign(links.size(), 0.0);
  for (std::size_t i = 0; i < links.size(); ++i) {
    b.lengths[i] = std::max(b.lengths[i], 2.0 * links[i].com.norm());
    if (links[i].parent >= 0) {
      auto& reach = b.lengths[static_cast<std::size_t>(links[i].parent)];
      reach = std::max(reach, links[i].origin.norm());
    }
  }
  for (double& l : b.lengths) l = std::max(l, 0.02);
  for (double l : b.lengths) b.widths.push_back(std::clamp(0.12 * l, 0.01, 0.08));
}

}  // namespace

int body_index(const SceneDescription& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

SceneDescription describe_scene(
    const core::Network& network, const toml::table& document,
    const std::map<std::string, std::vector<scene::UrdfVisual>>* robot_visuals) {
  SceneDescription scene;
  for (const auto& a : network.admittances()) {
    BodyVisual b;
    b.name = a->name();
    const toml::table* table = body_table(document, b.name);
    if (const auto* arm = dynamic_cast<const components::PlanarArm*>(a.get())) {
      b.kind = BodyVisual::Kind::arm;
      b.base = arm->params().base;
      b.plane_x = arm->plane_x();
      b.plane_y = arm->plane_y();
      b.axis = arm->params().axis;
      const toml::array* links = table ? (*table)["links"].as_array() : nullptr;
      for (std::size_t i = 0; i < arm->params().links.size(); ++i) {
        const double length = arm->params().links[i].length;
        double width = 0.0;
        if (links && i < links->size()) {
          if (const toml::table* link = (*links)[i].as_table()) {
            width = (*link)["width"].value<double>().value_or(0.0);
          }
        }
        b.lengths.push_back(length);
        b.widths.push_back(width > 0.0 ? width : 0.1 * length);
      }
    } else if (const auto* tree = dynamic_cast<const components::SpatialTree*>(a.get())) {
      describe_tree(b, *tree);
      if (robot_visuals) {
        if (const auto it = robot_visuals->find(b.name); it != robot_visuals->end()) {
          b.visuals = it->second;
          // Meshes are not drawn (no mesh import yet): say so once per file.
          std::vector<std::string> told;
          for (const auto& v : b.visuals) {
            if (v.shape != scene::UrdfVisual::Shape::mesh ||
                std::find(told.begin(), told.end(), v.mesh) != told.end()) {
              continue;
            }
            told.push_back(v.mesh);
            std::fprintf(stderr, "warning: %s: mesh visual '%s' not drawn (meshes are not supported)\n",
                         b.name.c_str(), v.mesh.c_str());
          }
        }
      }
    } else if (dynamic_cast<const components::RigidBody*>(a.get())) {
      const std::string shape = table ? (*table)["shape"].value_or(std::string()) : "";
      if (shape == "box") {
        b.kind = BodyVisual::Kind::box;
        b.size = vec3_of((*table)["size"], b.size);
      } else if (shape == "cylinder") {
        describe_cylinder(*table, b);
      } else {
        b.kind = BodyVisual::Kind::sphere;
        b.radius = table ? (*table)["radius"].value<double>().value_or(0.1) : 0.1;
      }
    } else if (dynamic_cast<const components::PointMass*>(a.get())) {
      b.kind = BodyVisual::Kind::block;
    } else {
      continue;  // an admittance with no pose of its own
    }
    scene.bodies.push_back(std::move(b));
  }
  const toml::table* contact_tables = document["impedances"].as_table();
  std::vector<std::string> drawn;  // contact tables whose surface is drawn already
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const core::Impedance* imp = network.impedances()[i].get();
    const auto* fixed = dynamic_cast<const components::KikuuweContact*>(imp);
    const auto* moving = dynamic_cast<const components::MovingContact*>(imp);
    if (!fixed && !moving) continue;
    const components::KikuuweContactParams& params = fixed ? fixed->params() : moving->params();
    // The element of a contact point "NAME.i" comes from the table NAME.
    std::string table_name = imp->name();
    if (!(contact_tables && (*contact_tables)[table_name].as_table())) {
      table_name = table_name.substr(0, table_name.rfind('.'));
    }
    const bool several = table_name != imp->name();
    SurfaceVisual s{params.normal.normalized(), params.offset, params.extent, moving};
    if (std::find(drawn.begin(), drawn.end(), table_name) == drawn.end()) {
      drawn.push_back(table_name);
      const bool seen =
          !moving && !params.extent.bounded() &&
          std::any_of(scene.surfaces.begin(), scene.surfaces.end(), [&](const auto& o) {
            return !o.moving && !o.extent.bounded() && (o.normal - s.normal).norm() < 1e-9 &&
                   std::abs(o.offset - s.offset) < 1e-9;
          });
      if (!seen) scene.surfaces.push_back(s);
    }
    // The contact's body, from its map; a trail only for a single contact point.
    const auto wired = network.map_of(static_cast<int>(i)).admittances();
    const std::string body = wired.empty() ? "" : wired.front()->name();
    const toml::table* t = contact_tables ? (*contact_tables)[table_name].as_table() : nullptr;
    for (auto& b : scene.bodies) {
      if (b.name != body) continue;
      if (b.kind == BodyVisual::Kind::block) b.up = s.normal;
      if (several) continue;
      ContactVisual c{imp->name(), body, b.kind == BodyVisual::Kind::sphere ? b.radius : 0.0,
                      s.normal, s.offset};
      if (t && (*t)["radius"].is_number())
        c.radius = (*t)["radius"].value<double>().value_or(c.radius);
      scene.contacts.push_back(c);
    }
  }
  auto index_of = [&](const core::Admittance* a) {
    return a != nullptr ? body_index(scene, a->name()) : -1;
  };
  const toml::table* imps = document["impedances"].as_table();
  for (std::size_t i = 0; i < network.impedances().size(); ++i) {
    const auto* joint =
        dynamic_cast<const components::PenaltyJoint*>(network.impedances()[i].get());
    if (!joint) continue;
    // The map lists the child first, then the parent (none: the ground).
    const auto wired = network.map_of(static_cast<int>(i)).admittances();
    JointVisual j;
    j.name = joint->name();
    j.child = wired.empty() ? -1 : index_of(wired[0]);
    j.parent = wired.size() > 1 ? index_of(wired[1]) : -1;
    if (j.child < 0 || (wired.size() > 1 && j.parent < 0)) continue;
    const toml::table* t = imps ? (*imps)[j.name].as_table() : nullptr;
    if (t) {
      j.point = vec3_of((*t)["point"], j.point);
      j.parent_point = vec3_of((*t)["parent_point"], j.parent_point);
    }
    j.axis = joint->params().axis_child.normalized();
    const BodyVisual& c = scene.bodies[static_cast<std::size_t>(j.child)];
    if (c.kind == BodyVisual::Kind::box) j.width = c.size.minCoeff();
    if (c.kind == BodyVisual::Kind::sphere) j.width = c.radius;
    scene.joints.push_back(j);
  }
  describe_mechanism(network, document, scene);  // springs, dampers, sources
  return scene;
}

}  // namespace stiction::render
