// Elements a program supplies in code rather than in the scene file (the Python module's
// callables and subclassed impedances; docs/scene_format.md, "Elements supplied in code"):
// - a source law, for a torque_source or force_source declared in the file: it replaces the
//   file's `torque` / `force` (then only a placeholder) and is evaluated at every integrator
//   stage from the stage state, exactly as an expression of the scene's signals is;
// - an impedance, for a table `[impedances.NAME] type = "external"` whose keys choose its
//   wiring: the element itself comes from a factory called once per scene build, so every
//   run (a sweep's points, a study's runs) gets a fresh one.
// Both are looked up by the component's name. A SceneSource carries them, so that every
// service loading fresh copies of a scene sees them too.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/impedance.hpp"

namespace stiction::scene {

// One evaluation of a source law: the `values` (1 torque in N·m or 3 force entries in N)
// at stage time t (s) from the stage values of the signals it reads, in the order it named.
using SourceLaw = std::function<void(double t, const double* signals, double* values)>;

struct ExternalSource {
  // The signals the law reads, by CSV column name ("arm.theta.0"); nullopt: every signal
  // of the scene's admittances (the body states), in column order.
  std::optional<std::vector<std::string>> signals;
  // Called once per scene build with the names of the signals the law receives, in order,
  // and the number of values it writes (1 or 3); returns the law for that build.
  std::function<SourceLaw(const std::vector<std::string>& signals, int values)> make;
};

// Makes the element named `name`, fresh for every scene build. Its input and output sizes
// must fit the wiring its table chooses (checked at the table).
using ImpedanceFactory = std::function<std::unique_ptr<core::Impedance>(const std::string& name)>;

struct ExternalElements {
  std::map<std::string, ExternalSource> sources;       // by torque_source / force_source name
  std::map<std::string, ImpedanceFactory> impedances;  // by `type = "external"` table name
  // By name, text that changes whenever the element's behaviour may (its source code and
  // the values it reads), from the program that supplied it; the step check's cache keys on
  // it. An element without one (empty, or absent) keeps its scene out of the cache.
  std::map<std::string, std::string> fingerprints;
  // Whether every source and impedance here has a fingerprint.
  bool fingerprinted() const {
    const auto has = [this](const std::string& name) {
      const auto it = fingerprints.find(name);
      return it != fingerprints.end() && !it->second.empty();
    };
    for (const auto& [name, s] : sources) {
      if (!has(name)) return false;
    }
    for (const auto& [name, f] : impedances) {
      if (!has(name)) return false;
    }
    return true;
  }
};

}  // namespace stiction::scene
