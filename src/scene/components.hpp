// Factories for the component tables of a scene: [bodies.NAME] (admittances) and
// [impedances.NAME] (impedances with their wiring). One place holds the defaults and ranges
// of every key (docs/scene_format.md lists them).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/body.hpp"
#include "core/network.hpp"
#include "scene/settle.hpp"
#include "scene/toml_reader.hpp"

namespace stiction::scene {

class ComponentBuilder {
 public:
  ComponentBuilder(core::Network& network, const core::Vec3& gravity)
      : network_(network), gravity_(gravity) {}

  // The entries of [bodies] or [impedances] in file order (toml++ keeps keys sorted; the
  // state layout and the CSV columns follow the order the author wrote).
  std::vector<TableReader> entries(TableReader& section);

  void add_body(TableReader& table);
  void add_impedance(TableReader& table);
  // After every component: bodies whose contacts ask for `settle` start in equilibrium.
  void finish();

  const std::map<std::string, double>& stick_thresholds() const { return stick_thresholds_; }

 private:
  struct BodyInfo {
    core::Admittance* admittance = nullptr;
    double sphere_radius = 0.0;  // for the default contact radius; 0 if not a sphere
    core::Vec3 box_size = core::Vec3::Zero();  // a box's sides (its corners are contact points)
  };
  // kikuuwe_contact (contact_builder.cpp): one element per contact point.
  void add_contact(TableReader& table, const std::string& name);

  void check_name(TableReader& table);
  const BodyInfo& body(TableReader& table, std::string_view key);
  const core::Body* pose_body(TableReader& table, std::string_view key);
  // The CSV column names of every body's signals: what expressions may use.
  std::vector<std::string> observable_signals() const;
  // torque_source and force_source (sources.cpp).
  // `joint`: the joint wiring when `body` is an arm (torque_source), else nullptr.
  void add_source(TableReader& table, const std::string& type,
                  std::unique_ptr<core::CoordinateMap> joint,
                  std::unique_ptr<core::Impedance>& impedance,
                  std::unique_ptr<core::CoordinateMap>& map);

  core::Network& network_;
  core::Vec3 gravity_;
  std::map<std::string, BodyInfo> bodies_;
  std::map<std::string, std::string> impedance_types_;
  std::map<std::string, double> stick_thresholds_;
  core::Admittance* clock_ = nullptr;  // time for moving surfaces, made on first use
  std::vector<SettleBody> settle_;     // bodies to start in equilibrium (settle.cpp)
};

}  // namespace stiction::scene
