// `[impedances.NAME] type = "external"`: an impedance supplied in code
// (scene/external_elements.hpp), wired by its table's keys as a source would be: `body` and
// `joint` for a joint of a planar_arm; `body`, `axis` (and `parent`) for a torque about an
// axis of a rigid body; `body`, `point` and `frame` for a force at a point of a body. Part
// of ComponentBuilder.
#include <stdexcept>

#include "core/capabilities.hpp"
#include "scene/components.hpp"

namespace stiction::scene {

namespace {

std::string names_of(const auto& map) {
  std::string out;
  for (const auto& [name, value] : map) out += (out.empty() ? "'" : ", '") + name + "'";
  return out;
}

}  // namespace

void ComponentBuilder::add_external(TableReader& table, const std::string& name,
                                    std::unique_ptr<core::CoordinateMap> joint) {
  const ImpedanceFactory* factory = nullptr;
  if (externals_ != nullptr) {
    const auto found = externals_->impedances.find(name);
    if (found != externals_->impedances.end()) factory = &found->second;
  }
  if (factory == nullptr) {
    table.fail("type",
               "no element named '" + name +
                   "' was supplied in code (an external element comes from the program that "
                   "loads the scene: Python's scene.set_element(\"" +
                   name + "\", ...))");
  }
  std::unique_ptr<core::CoordinateMap> map = std::move(joint);
  std::string wiring = "a joint (position and rate in, a torque out)";
  if (!map && (table.has("axis") || table.has("parent"))) {
    map = axis_torque_map(table);
    wiring = "a torque about an axis (angle and rate in, a torque out)";
  } else if (!map) {
    map = body_force_map(table);
    wiring = "a force at a point (position and velocity, 6 entries, in; a force, 3, out)";
  }
  std::unique_ptr<core::Impedance> impedance;
  try {
    impedance = (*factory)(name);
  } catch (const std::invalid_argument& e) {
    throw InputError::at(table.table().source(), table.path() + ": " + e.what());
  }
  if (!impedance) table.fail("type", "the element supplied in code for '" + name + "' is missing");
  if (impedance->input_size() != map->motion_size() ||
      impedance->output_size() != map->force_size()) {
    table.fail("type", "the element supplied in code takes " +
                           std::to_string(impedance->input_size()) + " inputs and gives " +
                           std::to_string(impedance->output_size()) +
                           " outputs, but its wiring is " + wiring + ": input_size " +
                           std::to_string(map->motion_size()) + ", output_size " +
                           std::to_string(map->force_size()));
  }
  if (impedance->state_size() < 0) table.fail("type", "the element's state_size is negative");
  // A sliding pair gets stick/slip events, as the bundled friction elements do.
  if (core::capabilities_of(*impedance).slip != nullptr) {
    stick_thresholds_[name] = table.positive("stick_threshold", 1e-3);
  }
  table.finish();
  impedance_types_.emplace(name, "external");
  add_element(std::move(impedance), std::move(map));
}

void ComponentBuilder::check_externals_used() const {
  if (externals_ == nullptr) return;
  for (const auto& [name, law] : externals_->sources) {
    const auto type = impedance_types_.find(name);
    if (type == impedance_types_.end() ||
        (type->second != "torque_source" && type->second != "force_source")) {
      std::map<std::string, std::string> sources;
      for (const auto& [n, t] : impedance_types_) {
        if (t == "torque_source" || t == "force_source") sources.emplace(n, t);
      }
      throw InputError("a source law was supplied in code for '" + name +
                       "', but the scene has no torque_source or force_source of that name" +
                       (sources.empty() ? std::string(" (it has none)")
                                        : " (its sources: " + names_of(sources) + ")"));
    }
  }
  for (const auto& [name, factory] : externals_->impedances) {
    const auto type = impedance_types_.find(name);
    if (type == impedance_types_.end() || type->second != "external") {
      throw InputError(
          "an element was supplied in code for '" + name + "', but the scene has no [impedances." +
          name + "] with type = \"external\"" +
          (type == impedance_types_.end() ? std::string() : " (it is a " + type->second + ")"));
    }
  }
}

}  // namespace stiction::scene
