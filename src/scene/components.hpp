// Factories for the component tables of a scene: [bodies.NAME] (admittances) and
// [impedances.NAME] (impedances with their wiring). One place holds the defaults and ranges
// of every key (docs/scene_format.md lists them).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "components/maps/cylinder_rim_map.hpp"
#include "components/maps/observing_map.hpp"
#include "core/body.hpp"
#include "core/network.hpp"
#include "scene/drawing.hpp"
#include "scene/expression.hpp"
#include "scene/external_elements.hpp"
#include "scene/settle.hpp"
#include "scene/toml_reader.hpp"
#include "scene/urdf_loader.hpp"

namespace stiction::scene {

// Why `name` cannot name a component (or a spatial_tree joint: both name CSV columns), or
// empty: letters, digits, '_' and '-' only, no '.', 1 to 200 characters.
std::string component_name_problem(const std::string& name);

// Why `name` cannot name a signal or a state of an element (the SIGNAL part of a column
// NAME.SIGNAL[.AXIS], from a Python element's `signals` or `state_labels`), or empty:
// letters, digits, '_', '-' and inner '.', 1 to 200 characters (no comma, quote, space or
// control character: the CSV header is never quoted).
std::string signal_name_problem(const std::string& name);

// A torque_source or force_source as read from its table; wired in ComponentBuilder::finish(),
// once every signal its expressions may read (any component's, including later ones) is known.
struct SourceSpec {
  struct Entry {
    double constant = 0.0;
    bool is_expression = false;
    std::string text{};  // the expression
    toml::source_region where{};
    std::string what{};  // its key, for messages
  };
  std::string name, type, signal_name;
  std::unique_ptr<core::CoordinateMap> map;  // what it drives
  std::vector<Entry> entries;
  // A law supplied in code (scene/external_elements.hpp): replaces the entries' values.
  const ExternalSource* external = nullptr;
  toml::source_region where{};  // its table, for messages
};

class ComponentBuilder {
 public:
  // `externals`: the elements supplied in code (null: none); they must outlive the builder.
  ComponentBuilder(core::Network& network, const core::Vec3& gravity,
                   const ExternalElements* externals = nullptr)
      : network_(network), gravity_(gravity), externals_(externals) {}

  // The entries of [bodies] or [impedances] in file order (toml++ keeps keys sorted; the
  // state layout and the CSV columns follow the order the author wrote).
  std::vector<TableReader> entries(TableReader& section);

  void add_body(TableReader& table);
  void add_impedance(TableReader& table);
  // After every component: wires the sources' expressions, adds the impedances to the
  // network in file order, and starts the bodies whose contacts ask for `settle` in
  // equilibrium.
  void finish();
  // After the network is finalized: tells the maps that observe impedances where those
  // impedances' states are.
  void locate_observed();

  const std::map<std::string, double>& stick_thresholds() const { return stick_thresholds_; }
  // The directory a urdf body's relative `file` is found from (the scene file's).
  void set_directory(std::filesystem::path directory) { directory_ = std::move(directory); }
  // What is drawn, filled as each element is built (scene/drawing.hpp).
  Drawing& drawing() { return drawing_; }
  // The sources' expressions, for the check over the run's time span (Scene::expressions).
  const std::vector<std::shared_ptr<const Expression>>& expressions() const { return expressions_; }

 private:
  struct BodyInfo {
    core::Admittance* admittance = nullptr;
    double sphere_radius = 0.0;  // for the default contact radius; 0 if not a sphere
    core::Vec3 box_size = core::Vec3::Zero();  // a box's sides (its corners are contact points)
    // A cylinder's geometry: its contacts are rim points (components/maps/cylinder_rim_map).
    std::optional<components::CylinderShape> cylinder{};
  };
  // type = "urdf" (urdf_body.cpp): the tree, its joint elements queued in pending_.
  std::unique_ptr<core::Admittance> add_urdf_body(TableReader& table, const std::string& name);
  // type = "spatial_tree" (spatial_body.cpp).
  std::unique_ptr<core::Admittance> add_spatial_tree(TableReader& table, const std::string& name);
  // kikuuwe_contact (contact_builder.cpp): one element per contact point.
  void add_contact(TableReader& table, const std::string& name);
  // kikuuwe_contact with `other`: a contact between two bodies (pair_contact_builder.cpp).
  void add_pair_contact(TableReader& table, const std::string& name);
  // Refuses (at the table) `count` more contact elements when the scene would then hold more
  // than kMaxSceneContactElements (issue 39: 500 spheres with pairwise contacts ended in
  // std::bad_alloc after loading).
  void count_contact_elements(TableReader& table, std::size_t count);

  void check_name(TableReader& table);
  const BodyInfo& body(TableReader& table, std::string_view key);
  const core::Body* pose_body(TableReader& table, std::string_view key);
  // An impedance to add to the network, in file order; a source is built in finish().
  struct Pending {
    std::unique_ptr<core::Impedance> impedance;
    std::unique_ptr<core::CoordinateMap> map;
    std::unique_ptr<SourceSpec> source;
  };
  void add_element(std::unique_ptr<core::Impedance> impedance,
                   std::unique_ptr<core::CoordinateMap> map);
  // A friction element on joint `joint` of a planar arm (`body`): a joint site of the drawing
  // (its stick/slip badge). Nothing for an element on points (joint < 0).
  void add_joint_site(TableReader& table, const std::string& name, int joint);
  // torque_source and force_source (sources.cpp).
  // `joint`: the joint wiring when `body` is an arm (torque_source), else nullptr.
  void add_source(TableReader& table, const std::string& type,
                  std::unique_ptr<core::CoordinateMap> joint);
  // The wiring of a torque about `axis` between `body` and `parent` (rigid bodies), and of
  // a force at `point` of `body` in `frame` (sources.cpp).
  std::unique_ptr<core::CoordinateMap> axis_torque_map(TableReader& table);
  std::unique_ptr<core::CoordinateMap> body_force_map(TableReader& table);
  // `type = "external"`: an element supplied in code, wired by its table's keys
  // (external_elements.cpp). `joint`: as for add_source.
  void add_external(TableReader& table, const std::string& name,
                    std::unique_ptr<core::CoordinateMap> joint);
  // Every element supplied in code names a component of the scene of its kind.
  void check_externals_used() const;
  // Compiles the sources' expressions against every signal of the scene, rejects loops
  // between sources, and builds them (sources.cpp).
  void wire_sources();

  core::Network& network_;
  core::Vec3 gravity_;
  const ExternalElements* externals_;
  std::map<std::string, BodyInfo> bodies_;
  std::map<std::string, std::string> impedance_types_;
  std::map<std::string, double> stick_thresholds_;
  // Contact elements built so far (points, corners, rim points, pairs): bounded over the
  // whole scene (count_contact_elements).
  std::size_t contact_elements_ = 0;
  std::filesystem::path directory_;
  Drawing drawing_;
  core::Admittance* clock_ = nullptr;  // time for moving surfaces, made on first use
  std::vector<SettleBody> settle_;     // bodies to start in equilibrium (settle.cpp)
  std::vector<Pending> pending_;       // impedances not yet in the network
  // Maps of sources that read elements' outputs (owned by the network).
  std::vector<components::ObservingMap*> observers_;
  std::vector<std::shared_ptr<const Expression>> expressions_;
};

}  // namespace stiction::scene
