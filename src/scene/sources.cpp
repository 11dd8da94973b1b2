// Sources of the scene: torque_source and force_source, whose values are numbers or
// expressions of t and of the bodies' signals (feedback). Part of ComponentBuilder; kept
// apart from components.cpp because expressions of the state need the observing wiring.
#include <algorithm>
#include <cmath>
#include <memory>

#include "components/impedance/torque_source.hpp"
#include "components/maps/body_frame_point_map.hpp"
#include "components/maps/observing_map.hpp"
#include "components/maps/point_map.hpp"
#include "scene/axis_torque_map.hpp"
#include "scene/components.hpp"
#include "scene/expression.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

// One entry of a source before wiring: a constant or a compiled expression.
struct Entry {
  double constant = 0.0;
  std::shared_ptr<Expression> expression;  // null: the constant
};

Entry entry_of(const toml::node& node, const std::string& what, TableReader& table,
               std::string_view key, const std::vector<std::string>& signals) {
  if (node.is_number()) {
    return {finite_number(node, table.path() + "." + std::string(key)), nullptr};
  }
  if (!node.is_string()) {
    table.fail(key, "expected a number or an expression (a string) of t and the bodies' signals");
  }
  return {0.0, std::make_shared<Expression>(node.as_string()->get(), node.source(), what, signals)};
}

}  // namespace

std::vector<std::string> ComponentBuilder::observable_signals() const {
  std::vector<std::string> names;
  for (const auto& a : network_.admittances()) {
    const auto columns = core::column_names(a->name(), a->signals());
    names.insert(names.end(), columns.begin(), columns.end());
  }
  return names;
}

void ComponentBuilder::add_source(TableReader& table, const std::string& type,
                                  std::unique_ptr<core::CoordinateMap> joint,
                                  std::unique_ptr<core::Impedance>& impedance,
                                  std::unique_ptr<core::CoordinateMap>& map) {
  const std::string name = table.path().substr(table.path().rfind('.') + 1);
  const std::vector<std::string> signals = observable_signals();
  std::vector<Entry> entries;
  std::string signal_name;
  if (type == "torque_source") {
    signal_name = "tau";
    map = std::move(joint);
    if (!map) {
      const core::Body* child = pose_body(table, "body");
      const core::Body* parent = table.has("parent") ? pose_body(table, "parent") : nullptr;
      if (!child->can_rotate() || (parent != nullptr && !parent->can_rotate())) {
        table.fail("body", "a torque needs bodies that rotate (rigid_body) or a planar_arm joint");
      }
      if (parent == child) table.fail("parent", "must differ from `body`");
      const Vec3 axis = table.vec3("axis", Vec3::UnitZ());
      if (!(axis.norm() > 1e-12)) table.fail("axis", "must be a non-zero vector");
      map = std::make_unique<AxisTorqueMap>(*child, parent, axis.normalized());
    }
    const toml::node* node = table.node("torque");
    if (node == nullptr) table.fail("torque", "missing (a number or an expression is required)");
    entries.push_back(entry_of(*node, table.path() + ".torque", table, "torque", signals));
  } else {  // force_source
    signal_name = "f";
    const core::Body* body = pose_body(table, "body");
    const Vec3 point = table.vec3("point", Vec3::Zero());
    const std::string frame = table.string("frame", "world");
    if (frame == "world") {
      map = std::make_unique<components::PointMap>(*body, point, nullptr, Vec3::Zero());
    } else if (frame == "body") {
      map = std::make_unique<components::BodyFramePointMap>(*body, point);
    } else {
      table.fail("frame", "expected \"world\" or \"body\", got \"" + frame + "\"");
    }
    const toml::node* node = table.node("force");
    if (node == nullptr) table.fail("force", "missing (3 numbers or expressions, [fx, fy, fz])");
    const toml::array* array = node->as_array();
    if (array == nullptr || array->size() != 3) {
      table.fail("force", "expected an array of 3 entries (numbers or expressions), [fx, fy, fz]");
    }
    for (std::size_t i = 0; i < 3; ++i) {
      entries.push_back(entry_of(*array->get(i), table.path() + ".force[" + std::to_string(i) + "]",
                                 table, "force", signals));
    }
  }

  // The signals the expressions use, once each: the map observes them from the stage state.
  std::vector<std::string> observed;
  for (const Entry& e : entries) {
    if (!e.expression) continue;
    for (const auto& s : e.expression->used_signals()) {
      if (std::find(observed.begin(), observed.end(), s) == observed.end()) observed.push_back(s);
    }
  }
  std::vector<components::TorqueSource::StateProfile> profiles;
  for (const Entry& e : entries) {
    if (!e.expression) {
      profiles.emplace_back([v = e.constant](double, const double*) { return v; });
      continue;
    }
    // Where the expression's values sit among the observed ones; gathered into a buffer
    // sized here, so a stage evaluation does not allocate.
    std::vector<int> index;
    for (const auto& s : e.expression->used_signals()) {
      index.push_back(
          static_cast<int>(std::find(observed.begin(), observed.end(), s) - observed.begin()));
    }
    auto buffer = std::make_shared<std::vector<double>>(index.size());
    profiles.emplace_back(
        [expression = e.expression, index, buffer](double t, const double* values) {
          for (std::size_t k = 0; k < index.size(); ++k) (*buffer)[k] = values[index[k]];
          return expression->evaluate(t, buffer->data());
        });
  }
  if (!observed.empty()) {
    std::vector<components::ObservingMap::Observed> wiring;
    for (const auto& s : observed) {
      const std::string component = s.substr(0, s.find('.'));
      const core::Admittance* a = network_.find_admittance(component);
      const auto columns = core::column_names(a->name(), a->signals());
      const int entry =
          static_cast<int>(std::find(columns.begin(), columns.end(), s) - columns.begin());
      wiring.push_back({a, entry});
    }
    map = std::make_unique<components::ObservingMap>(std::move(map), std::move(wiring));
  }
  impedance = std::make_unique<components::TorqueSource>(
      name, std::move(profiles), static_cast<int>(observed.size()), signal_name, type);
}

}  // namespace stiction::scene
