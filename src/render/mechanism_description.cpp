#include "render/mechanism_description.hpp"

#include "components/impedance/line_spring_damper.hpp"
#include "components/impedance/spring_damper.hpp"
#include "components/impedance/torque_source.hpp"

namespace stiction::render {
namespace {

core::Vec3 vec3_or(const toml::table& t, const char* key, const core::Vec3& fallback) {
  const toml::array* a = t[key].as_array();
  if (!a || a->size() != 3) return fallback;
  core::Vec3 v;
  for (int i = 0; i < 3; ++i) {
    v[i] = (*a)[static_cast<std::size_t>(i)].value<double>().value_or(fallback[i]);
  }
  return v;
}

}  // namespace

void describe_mechanism(const core::Network& network, const toml::table& document,
                        SceneDescription& scene) {
  const toml::table* tables = document["impedances"].as_table();
  if (!tables) return;
  for (const auto& imp : network.impedances()) {
    const toml::table* t = (*tables)[imp->name()].as_table();
    if (!t) continue;
    const int body = body_index(scene, (*t)["body"].value_or(std::string()));
    if (body < 0) continue;
    const BodyVisual::Kind kind = scene.bodies[static_cast<std::size_t>(body)].kind;
    const bool on_arm = kind == BodyVisual::Kind::arm || kind == BodyVisual::Kind::tree;
    const bool spring = dynamic_cast<const components::SpringDamper*>(imp.get()) != nullptr ||
                        dynamic_cast<const components::LineSpringDamper*>(imp.get()) != nullptr;
    if (spring && !on_arm) {
      // An end on an arm has no pose of its own to hang a coil on: not drawn.
      const int other = body_index(scene, (*t)["other"].value_or(std::string()));
      if (other >= 0 &&
          jointed(scene.bodies[static_cast<std::size_t>(other)])) {
        continue;
      }
      SpringVisual s;
      s.name = imp->name();
      s.body = body;
      s.point = vec3_or(*t, "point", s.point);
      s.other = other;
      s.other_point = vec3_or(*t, "other_point", s.other_point);
      s.damping = (*t)["damping"].value<double>().value_or(0.0);
      s.free_length = (*t)["length"].value<double>().value_or(0.0);
      scene.springs.push_back(s);
      continue;
    }
    if (dynamic_cast<const components::TorqueSource*>(imp.get()) == nullptr) continue;
    SourceVisual s;
    s.name = imp->name();
    s.body = body;
    if (imp->type() == "force_source") {
      if (on_arm) continue;
      s.kind = SourceVisual::Kind::force;
      s.point = vec3_or(*t, "point", s.point);
      s.body_frame = (*t)["frame"].value_or(std::string("world")) == "body";
    } else {
      s.kind = SourceVisual::Kind::torque;
      if (on_arm) {
        s.joint = static_cast<int>((*t)["joint"].value<long>().value_or(0));
      } else {
        const core::Vec3 axis = vec3_or(*t, "axis", core::Vec3::UnitZ());
        s.axis = axis.norm() > 1e-12 ? core::Vec3(axis.normalized()) : core::Vec3::UnitZ();
      }
    }
    scene.sources.push_back(s);
  }
}

}  // namespace stiction::render
