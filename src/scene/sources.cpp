// Sources of the scene: torque_source and force_source, whose values are numbers or
// expressions of t and of any signal of the scene by its CSV column name: a body's state
// (feedback) or another element's output (a contact's friction force, a spring's force),
// evaluated at every integrator stage from the stage state. Part of ComponentBuilder; kept
// apart from components.cpp because expressions of the state need the observing wiring.
//
// Sources are read with their table but built in finish(): an expression may name a
// component written later in the file. Only sources read other elements' outputs, so an
// algebraic loop (a source's value depending on itself, directly or through other sources)
// is a cycle among sources, rejected at the name that closes it.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "components/impedance/torque_source.hpp"
#include "components/maps/body_frame_point_map.hpp"
#include "components/maps/observing_map.hpp"
#include "components/maps/point_map.hpp"
#include "core/safe_normalize.hpp"
#include "scene/axis_torque_map.hpp"
#include "scene/components.hpp"
#include "scene/expression.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

SourceSpec::Entry entry_of(const toml::node& node, const std::string& what, TableReader& table,
                           std::string_view key) {
  if (node.is_number()) return {.constant = finite_number(node, what)};
  if (!node.is_string()) {
    table.fail(key, "expected a number or an expression (a string) of t and the scene's signals");
  }
  return {
      .is_expression = true, .text = node.as_string()->get(), .where = node.source(), .what = what};
}

// Where a signal comes from: a column of an admittance, or of the pending impedance `element`.
struct Column {
  const core::Admittance* admittance = nullptr;
  int element = -1;  // index into pending_
  int entry = 0;     // index among its component's columns
};

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

void ComponentBuilder::add_source(TableReader& table, const std::string& type,
                                  std::unique_ptr<core::CoordinateMap> joint) {
  auto spec = std::make_unique<SourceSpec>();
  spec->name = table.path().substr(table.path().rfind('.') + 1);
  spec->type = type;
  spec->where = table.table().source();
  if (externals_ != nullptr) {
    const auto law = externals_->sources.find(spec->name);
    if (law != externals_->sources.end()) spec->external = &law->second;
  }
  // With a law supplied in code the file's value is a placeholder, and may be left out.
  const bool placeholder = spec->external != nullptr;
  if (type == "torque_source") {
    spec->signal_name = "tau";
    spec->map = joint ? std::move(joint) : axis_torque_map(table);
    const toml::node* node = table.node("torque");
    if (node != nullptr) {
      spec->entries.push_back(entry_of(*node, table.path() + ".torque", table, "torque"));
    } else if (placeholder) {
      spec->entries.emplace_back();
    } else {
      table.fail("torque", "missing (a number or an expression is required)");
    }
  } else {  // force_source
    spec->signal_name = "f";
    spec->map = body_force_map(table);
    const toml::node* node = table.node("force");
    if (node == nullptr && placeholder) {
      spec->entries.resize(3);
    } else {
      if (node == nullptr) table.fail("force", "missing (3 numbers or expressions, [fx, fy, fz])");
      const toml::array* array = node->as_array();
      if (array == nullptr || array->size() != 3) {
        table.fail("force",
                   "expected an array of 3 entries (numbers or expressions), [fx, fy, fz]");
      }
      for (std::size_t i = 0; i < 3; ++i) {
        spec->entries.push_back(entry_of(
            *array->get(i), table.path() + ".force[" + std::to_string(i) + "]", table, "force"));
      }
    }
  }
  pending_.push_back({nullptr, nullptr, std::move(spec)});
}

std::unique_ptr<core::CoordinateMap> ComponentBuilder::axis_torque_map(TableReader& table) {
  const core::Body* child = pose_body(table, "body");
  const core::Body* parent = table.has("parent") ? pose_body(table, "parent") : nullptr;
  if (!child->can_rotate() || (parent != nullptr && !parent->can_rotate())) {
    table.fail("body",
               "a torque needs bodies that rotate (rigid_body) or a joint of an arm "
               "(planar_arm, spatial_tree or urdf)");
  }
  if (parent == child) table.fail("parent", "must differ from `body`");
  const auto axis = core::safe_normalized(table.vec3("axis", Vec3::UnitZ()));
  if (!axis) table.fail("axis", "must be a non-zero vector");
  return std::make_unique<AxisTorqueMap>(*child, parent, *axis);
}

std::unique_ptr<core::CoordinateMap> ComponentBuilder::body_force_map(TableReader& table) {
  const core::Body* body = pose_body(table, "body");
  const Vec3 point = table.vec3("point", Vec3::Zero());
  const std::string frame = table.string("frame", "world");
  if (frame == "body") return std::make_unique<components::BodyFramePointMap>(*body, point);
  if (frame != "world")
    table.fail("frame", "expected \"world\" or \"body\", got \"" + frame + "\"");
  return std::make_unique<components::PointMap>(*body, point, nullptr, Vec3::Zero());
}

void ComponentBuilder::wire_sources() {
  check_externals_used();
  // A source's columns, from a source of the same shape (its signals do not depend on its law).
  auto source_columns = [](const SourceSpec& spec) {
    std::vector<components::TorqueSource::StateProfile> zero(
        spec.entries.size(), [](double, const double*) { return 0.0; });
    const components::TorqueSource shape(spec.name, std::move(zero), 0, spec.signal_name,
                                         spec.type);
    return core::column_names(shape.name(), shape.signals());
  };
  // Every signal of the scene by its CSV column name.
  std::vector<std::string> names;
  std::map<std::string, Column> columns;
  auto add = [&](const std::vector<std::string>& component, Column where) {
    for (const auto& c : component) {
      names.push_back(c);
      columns[c] = where;
      ++where.entry;
    }
  };
  for (const auto& a : network_.admittances())
    add(core::column_names(a->name(), a->signals()), {a.get()});
  const std::vector<std::string> admittance_names = names;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    const Pending& p = pending_[i];
    add(p.source ? source_columns(*p.source)
                 : core::column_names(p.impedance->name(), p.impedance->signals()),
        {nullptr, static_cast<int>(i)});
  }

  // Compile every source's expressions, and note the signals each source reads, once each:
  // its map observes them from the stage state. A law supplied in code reads the signals it
  // names, or every admittance signal; its entries in the file are placeholders.
  std::vector<std::vector<std::shared_ptr<Expression>>> expressions(pending_.size());
  std::vector<std::vector<std::string>> observed(pending_.size());
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (!pending_[i].source) continue;
    const SourceSpec& spec = *pending_[i].source;
    if (spec.external != nullptr) {
      expressions[i].resize(spec.entries.size());
      observed[i] = spec.external->signals.value_or(admittance_names);
      for (std::size_t k = 0; k < observed[i].size(); ++k) {
        const std::string& s = observed[i][k];
        if (!columns.contains(s)) {
          throw InputError::at(
              spec.where,
              "impedances." + spec.name + ": the law supplied in code reads '" + s +
                  "', which is not a signal of the scene (signals: " + join_names(names) + ")");
        }
        if (std::find(observed[i].begin(), observed[i].begin() + static_cast<long>(k), s) !=
            observed[i].begin() + static_cast<long>(k)) {
          throw InputError::at(
              spec.where,
              "impedances." + spec.name + ": the law supplied in code names '" + s + "' twice");
        }
      }
      continue;
    }
    for (const auto& e : spec.entries) {
      expressions[i].push_back(
          e.is_expression ? std::make_shared<Expression>(e.text, e.where, e.what, names) : nullptr);
      if (!expressions[i].back()) continue;
      expressions_.push_back(expressions[i].back());
      for (const auto& s : expressions[i].back()->used_signals()) {
        if (std::find(observed[i].begin(), observed[i].end(), s) == observed[i].end())
          observed[i].push_back(s);
      }
    }
  }
  // Fails at what reads signal `s` of source `i`: the expression naming it, or the table of
  // a law supplied in code.
  auto fail_reading = [&](std::size_t i, const std::string& s, const std::string& message) {
    for (const auto& e : expressions[i]) {
      const auto& used = e ? e->used_signals() : std::vector<std::string>{};
      if (std::find(used.begin(), used.end(), s) != used.end()) e->fail_at(s, message);
    }
    throw InputError::at(
        pending_[i].source->where,
        "impedances." + pending_[i].source->name + ": the law supplied in code reads " + message);
  };
  // The sources `i` reads, each with the first name it reads it by.
  auto reads = [&](std::size_t i) {
    std::vector<std::pair<int, std::string>> out;
    for (const auto& s : observed[i]) {
      const int j = columns.at(s).element;
      if (j < 0 || !pending_[j].source) continue;
      if (std::none_of(out.begin(), out.end(), [&](const auto& o) { return o.first == j; }))
        out.emplace_back(j, s);
    }
    return out;
  };

  // Build in dependency order (a source after those it reads), rejecting cycles.
  enum class Mark { none, building, built };
  std::vector<Mark> mark(pending_.size(), Mark::none);
  std::vector<int> path;  // the sources being built, outermost first
  auto build = [&](auto& self, int i) -> void {
    mark[i] = Mark::building;
    path.push_back(i);
    for (const auto& [j, by] : reads(i)) {
      if (mark[j] == Mark::built) continue;
      if (mark[j] == Mark::building) {
        const std::string& name = pending_[i].source->name;
        if (j == i) {
          fail_reading(i, by,
                       "'" + by + "' is the output of this source ('" + name +
                           "'): a source may not read its own value (an algebraic loop)");
        }
        std::string chain;
        for (auto k = std::find(path.begin(), path.end(), j); k != path.end(); ++k)
          chain += pending_[*k].source->name + " -> ";
        fail_reading(i, by,
                     "'" + by + "' is the output of source '" + pending_[j].source->name +
                         "', which reads this source's value: an algebraic loop (" + chain +
                         pending_[j].source->name + "); a source may not depend on its own value");
      }
      self(self, j);
    }
    SourceSpec& spec = *pending_[i].source;
    std::vector<components::TorqueSource::StateProfile> profiles;
    if (spec.external != nullptr) {
      // One call of the law gives every entry: the first entry's profile calls it and the
      // others read what it wrote (TorqueSource::evaluate asks for the entries in order, at
      // the same stage).
      SourceLaw law = spec.external->make(observed[i], static_cast<int>(spec.entries.size()));
      auto values = std::make_shared<std::vector<double>>(spec.entries.size());
      profiles.emplace_back([law = std::move(law), values](double t, const double* signals) {
        law(t, signals, values->data());
        return (*values)[0];
      });
      for (std::size_t k = 1; k < spec.entries.size(); ++k)
        profiles.emplace_back([values, k](double, const double*) { return (*values)[k]; });
    } else {
      for (std::size_t k = 0; k < spec.entries.size(); ++k) {
        const auto& e = expressions[i][k];
        if (!e) {
          profiles.emplace_back(
              [v = spec.entries[k].constant](double, const double*) { return v; });
          continue;
        }
        // Where the expression's values sit among the observed ones; gathered into a buffer
        // sized here, so a stage evaluation does not allocate.
        std::vector<int> index;
        for (const auto& s : e->used_signals()) {
          index.push_back(static_cast<int>(std::find(observed[i].begin(), observed[i].end(), s) -
                                           observed[i].begin()));
        }
        auto buffer = std::make_shared<std::vector<double>>(index.size());
        profiles.emplace_back([expression = e, index, buffer](double t, const double* values) {
          for (std::size_t n = 0; n < index.size(); ++n) (*buffer)[n] = values[index[n]];
          return expression->evaluate(t, buffer->data());
        });
      }
    }
    std::unique_ptr<core::CoordinateMap> map = std::move(spec.map);
    int raw = 0;
    components::TorqueSource::Observer observer;
    if (!observed[i].empty()) {
      std::vector<components::ObservingMap::Observed> wiring;
      for (const auto& s : observed[i]) {
        const Column& c = columns.at(s);
        if (c.admittance) {
          wiring.push_back({.admittance = c.admittance, .entry = c.entry});
        } else {
          wiring.push_back({.impedance = pending_[c.element].impedance.get(),
                            .map = pending_[c.element].map.get(),
                            .entry = c.entry});
        }
      }
      auto observing =
          std::make_unique<components::ObservingMap>(std::move(map), std::move(wiring));
      raw = observing->raw_size();
      observer = [m = observing.get()](double t, double tau, const double* entries) {
        return m->values(t, tau, entries);
      };
      observers_.push_back(observing.get());
      map = std::move(observing);
    }
    pending_[i].impedance = std::make_unique<components::TorqueSource>(
        spec.name, std::move(profiles), raw, spec.signal_name, spec.type, std::move(observer));
    pending_[i].map = std::move(map);
    pending_[i].source.reset();
    mark[i] = Mark::built;
    path.pop_back();
  };
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (pending_[i].source && mark[i] == Mark::none) build(build, static_cast<int>(i));
  }
}

void ComponentBuilder::locate_observed() {
  for (components::ObservingMap* m : observers_) m->locate(network_);
}

}  // namespace stiction::scene
