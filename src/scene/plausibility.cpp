#include "scene/plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/capabilities.hpp"
#include "scene/scene.hpp"
#include "sys/terminal_text.hpp"

namespace stiction::scene {

namespace {

using core::Vec3;

// Bounds of the checks (docs/scene_format.md, "Plausibility warnings").
constexpr double kMaxMu = 2.0;                     // dry rubber on concrete is about 1
constexpr double kMinDensity = 1.0;                // kg/m^3: below foam, about air
constexpr double kMinShellDensity = 0.1;           // a hollow sphere: mass over enclosed volume
constexpr double kMaxDensity = 3.0e4;              // kg/m^3: above osmium (22600)
constexpr double kMaxGravity = 50.0;               // m/s^2: five times Earth's (9800 is mm/s^2)
constexpr double kGravityAlongNormal = 0.5;        // cos of 60 degrees
constexpr double kMaxTilt = std::numbers::pi / 2;  // a plane turned past vertical
constexpr double kMaxAngle = 2 * std::numbers::pi;
constexpr double kMinRows = 10.0;
// A body that starts this fraction of its size inside a surface or another body: its contact
// spring then holds 0.5 K d^2 of energy and launches it (issue 39).
constexpr double kMaxStartPenetration = 0.01;

std::string number_text(double x) {
  std::ostringstream out;
  out.precision(4);
  out << x;
  return out.str();
}

std::string vec_text(const Vec3& v) {
  std::ostringstream out;
  out.precision(4);
  out << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
  return out.str();
}

std::optional<double> number_of(const toml::node* node) {
  if (node == nullptr) return std::nullopt;
  if (const auto v = node->value<double>()) return *v;
  return std::nullopt;
}

std::optional<Vec3> vec3_of(const toml::node* node) {
  const toml::array* a = node != nullptr ? node->as_array() : nullptr;
  if (a == nullptr || a->size() != 3) return std::nullopt;
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const auto x = (*a)[static_cast<std::size_t>(i)].value<double>();
    if (!x) return std::nullopt;
    v[i] = *x;
  }
  return v;
}

// Collects warnings located at a key's value (or at its table when the key is absent).
class Collector {
 public:
  explicit Collector(const Scene& scene) : scene_(scene) {}

  void warn(const toml::node* at, const toml::node& table, const std::string& key,
            const std::string& text) {
    const toml::source_region& where = at != nullptr ? at->source() : table.source();
    Warning w;
    w.file = where.path ? *where.path : scene_.path.string();
    w.line = static_cast<long>(where.begin.line);
    w.column = static_cast<long>(where.begin.column);
    w.key = key;
    w.text = key + ": " + text;
    warnings_.push_back(std::move(w));
  }
  std::vector<Warning> take() {
    std::stable_sort(warnings_.begin(), warnings_.end(), [](const Warning& a, const Warning& b) {
      return a.line != b.line ? a.line < b.line : a.column < b.column;
    });
    return std::move(warnings_);
  }

 private:
  const Scene& scene_;
  std::vector<Warning> warnings_;
};

// The component tables of a section ("bodies", "impedances"), with their dotted paths.
std::vector<std::pair<std::string, const toml::table*>> components(const toml::table& doc,
                                                                   const char* section) {
  std::vector<std::pair<std::string, const toml::table*>> out;
  const toml::table* s = doc[section].as_table();
  if (s == nullptr) return out;
  for (const auto& [key, value] : *s) {
    if (const toml::table* t = value.as_table()) {
      out.emplace_back(std::string(section) + "." + std::string(key.str()), t);
    }
  }
  return out;
}

std::string type_of(const toml::table& t) { return t["type"].value_or(std::string{}); }

void check_simulation(const Scene& scene, Collector& out) {
  const toml::table* sim = scene.document["simulation"].as_table();
  if (sim == nullptr) return;
  const core::RunOptions& run = scene.run;
  // dt > duration is an error (core/run_limits.cpp), no longer a warning.
  if (run.duration * run.output_rate < kMinRows) {
    const bool rate_given = sim->contains("output_rate");
    out.warn(rate_given ? sim->get("output_rate") : sim->get("duration"), *sim,
             rate_given ? "simulation.output_rate" : "simulation.duration",
             "duration x output_rate = " + number_text(run.duration * run.output_rate) +
                 ": fewer than " + number_text(kMinRows) +
                 " rows (trajectory.csv and the plots have almost nothing to show)");
  }
}

// Mass over volume of a body with a shape, against the range of real materials.
void check_densities(const toml::table& doc, Collector& out) {
  for (const auto& entry : components(doc, "bodies")) {
    const std::string& path = entry.first;
    const toml::table* t = entry.second;  // (named: a lambda below captures it)
    const std::string type = type_of(*t);
    const auto mass = number_of(t->get("mass"));
    if (!mass || !(*mass > 0.0)) continue;
    auto check = [&](double volume, double min_density, const toml::node* at,
                     const std::string& key, const std::string& what) {
      if (!(volume > 0.0)) return;
      const double density = *mass / volume;
      if (density >= min_density && density <= kMaxDensity) return;
      out.warn(at, *t, key,
               "a mass of " + number_text(*mass) + " kg in " + what + " is a density of " +
                   number_text(density) + " kg/m^3, outside " + number_text(min_density) + " .. " +
                   number_text(kMaxDensity) + " (a unit mistake: cm or mm for m, g for kg?)");
    };
    if (type == "rigid_body") {
      const std::string shape = (*t)["shape"].value_or(std::string{});
      if (shape == "sphere" || shape == "hollow_sphere") {
        const auto r = number_of(t->get("radius"));
        if (!r) continue;
        check(4.0 / 3.0 * std::numbers::pi * *r * *r * *r,
              shape == "sphere" ? kMinDensity : kMinShellDensity, t->get("radius"),
              path + ".radius", "a sphere of radius " + number_text(*r) + " m");
      } else if (shape == "box") {
        const auto s = vec3_of(t->get("size"));
        if (!s) continue;
        check(s->prod(), kMinDensity, t->get("size"), path + ".size",
              "a box of " + vec_text(*s) + " m");
      }
    } else if (type == "planar_arm") {
      const toml::array* links = (*t)["links"].as_array();
      if (links == nullptr) continue;
      for (std::size_t i = 0; i < links->size(); ++i) {
        const toml::table* link = (*links)[i].as_table();
        if (link == nullptr) continue;
        const auto m = number_of(link->get("mass"));
        const auto length = number_of(link->get("length"));
        const auto width = number_of(link->get("width"));
        if (!m || !length || !width || !(*width > 0.0)) continue;  // a thin link has no volume
        const double volume = *length * *width * *width;
        const double density = *m / volume;
        if (density >= kMinDensity && density <= kMaxDensity) continue;
        const std::string key = path + ".links[" + std::to_string(i) + "]";
        out.warn(link->get("mass"), *link, key + ".mass",
                 "a link of " + number_text(*m) + " kg, " + number_text(*length) + " m x " +
                     number_text(*width) + " m x " + number_text(*width) + " m is a density of " +
                     number_text(density) + " kg/m^3, outside " + number_text(kMinDensity) +
                     " .. " + number_text(kMaxDensity) + " (a unit mistake?)");
      }
    }
  }
}

// Angles in degrees where radians are meant: arm angles, joint offsets past a full turn.
void check_angles(const toml::table& doc, Collector& out) {
  for (const auto& [path, t] : components(doc, "bodies")) {
    if (type_of(*t) != "planar_arm") continue;
    const toml::array* angles = (*t)["angles"].as_array();
    if (angles == nullptr) continue;
    for (const auto& a : *angles) {
      const auto v = a.value<double>();
      if (v && std::abs(*v) > kMaxAngle) {
        out.warn(&a, *t, path + ".angles",
                 "an initial joint angle of " + number_text(*v) +
                     " rad is more than a full turn: degrees where radians are meant?");
        break;
      }
    }
  }
  for (const auto& [path, t] : components(doc, "impedances")) {
    const std::string type = type_of(*t);
    if (type == "penalty_joint") {
      const auto offset = number_of(t->get("angle_offset"));
      if (offset && std::abs(*offset) > kMaxAngle) {
        out.warn(t->get("angle_offset"), *t, path + ".angle_offset",
                 number_text(*offset) +
                     " rad is more than a full turn: degrees where radians "
                     "are meant?");
      }
    } else if (type == "kikuuwe_contact") {
      const auto tilt = number_of(t->get("tilt"));
      if (tilt && std::abs(*tilt) > kMaxTilt) {
        out.warn(t->get("tilt"), *t, path + ".tilt",
                 "a tilt of " + number_text(*tilt) +
                     " rad turns the surface past vertical: degrees where radians are meant? (" +
                     number_text(*tilt) + " degrees is " +
                     number_text(*tilt * std::numbers::pi / 180.0) + " rad)");
      }
    } else if (type == "spring_damper") {
      // A joint spring's rest angle (its body is an arm).
      const std::string body = (*t)["body"].value_or(std::string{});
      const toml::table* b = doc["bodies"][body].as_table();
      const auto rest = number_of(t->get("rest"));
      if (b != nullptr && type_of(*b) == "planar_arm" && rest && std::abs(*rest) > kMaxAngle) {
        out.warn(t->get("rest"), *t, path + ".rest",
                 "a rest angle of " + number_text(*rest) +
                     " rad is more than a full turn: degrees where radians are meant?");
      }
    }
  }
}

// Gravity's size, and its direction against the contacts' normals.
void check_gravity_and_contacts(const Scene& scene, Collector& out) {
  const toml::table& doc = scene.document;
  const toml::node* gravity_node = doc.get("gravity");
  const Vec3 gravity = vec3_of(gravity_node).value_or(Vec3(0.0, 0.0, -9.8));
  if (gravity.norm() > kMaxGravity) {
    out.warn(gravity_node, doc, "gravity",
             "|gravity| = " + number_text(gravity.norm()) + " m/s^2 is more than " +
                 number_text(kMaxGravity) + " m/s^2 (9.8 m/s^2 on Earth; 9800 would be mm/s^2)");
  }
  std::vector<std::string> away;  // contacts gravity pulls bodies away from
  for (const auto& [path, t] : components(doc, "impedances")) {
    if (type_of(*t) != "kikuuwe_contact") continue;
    // One coefficient, or the larger of an anisotropic pair [mu_1, mu_2].
    std::optional<double> mu = number_of(t->get("mu"));
    if (const toml::array* pair = t->get("mu") != nullptr ? t->get("mu")->as_array() : nullptr) {
      for (const toml::node& entry : *pair) {
        const auto m = number_of(&entry);
        if (m && (!mu || *m > *mu)) mu = m;
      }
    }
    if (mu && *mu > kMaxMu) {
      out.warn(t->get("mu"), *t, path + ".mu",
               "mu = " + number_text(*mu) + " is above " + number_text(kMaxMu) +
                   " (dry rubber on concrete is about 1): a typo or a percentage?");
    }
    const Vec3 normal = vec3_of(t->get("normal")).value_or(Vec3(0.0, 0.0, 1.0));
    if (normal.norm() > 0.0 && gravity.norm() > 0.0 &&
        gravity.dot(normal) > kGravityAlongNormal * gravity.norm() * normal.norm()) {
      if (gravity_node == nullptr) {
        // Default gravity (down): this surface faces down, a ceiling.
        out.warn(t->get("normal"), *t, path + ".normal",
                 "the normal " + vec_text(normal) + " points along gravity " + vec_text(gravity) +
                     ": bodies fall away from this surface (a sign mistake?)");
      } else {
        away.push_back(path);
      }
    }
  }
  if (!away.empty()) {
    std::string list;
    for (const auto& p : away) list += (list.empty() ? "" : ", ") + p;
    out.warn(gravity_node, doc, "gravity",
             "gravity " + vec_text(gravity) + " points along the normal of " + list +
                 ": bodies fall away from the surface (gravity down is [0, 0, -9.8])");
  }
}

// The network elements of each impedance table, by the table's NAME: NAME itself, or NAME.i
// (the points of a contact). One pass, so the check below stays linear in the elements (a
// search per table made loading 40000 springs quadratic, issue 25). Component names hold no
// dot (refused in scene/components.cpp), so the part before the first dot is the table's name.
std::unordered_map<std::string, std::vector<int>> elements_by_table(const core::Network& network) {
  std::unordered_map<std::string, std::vector<int>> by_table;
  const auto& impedances = network.impedances();
  for (int i = 0; i < static_cast<int>(impedances.size()); ++i) {
    const std::string& name = impedances[i]->name();
    const std::size_t dot = name.find('.');
    if (dot != std::string::npos && name.find('.', dot + 1) != std::string::npos) continue;
    by_table[name.substr(0, dot)].push_back(i);
  }
  return by_table;
}

// `settle = true` where no point of the body touches the surface at t = 0 (settle only
// places bodies within 1 um of it), and stick thresholds above every speed in the scene.
void check_network(const Scene& scene, Collector& out) {
  core::Network& network = *scene.network;
  const core::Vec x0 = network.initial_state();
  const toml::table& doc = scene.document;
  const int count = static_cast<int>(network.impedances().size());

  double speed_scale = 0.0;  // the largest initial speed: slips, bodies, joint rates
  for (int i = 0; i < count; ++i) {
    if (const core::SlipElement* slip = network.capabilities(i).slip) {
      speed_scale =
          std::max(speed_scale, slip->slip_velocity(network.impedance_input(i, x0)).norm());
    }
  }
  for (const auto& [path, t] : components(doc, "bodies")) {
    if (const auto v = vec3_of(t->get("velocity"))) speed_scale = std::max(speed_scale, v->norm());
    if (const toml::array* rates = (*t)["rates"].as_array()) {
      for (const auto& r : *rates) speed_scale = std::max(speed_scale, std::abs(r.value_or(0.0)));
    }
  }

  const auto by_table = elements_by_table(network);
  for (const auto& [path, t] : components(doc, "impedances")) {
    const bool settle = (*t)["settle"].value_or(false);
    bool touches = false, any_contact = false;
    static const std::vector<int> none;
    const auto found = by_table.find(path.substr(path.find('.') + 1));
    for (const int i : found == by_table.end() ? none : found->second) {
      if (const core::NormalContact* c = network.capabilities(i).contact) {
        any_contact = true;
        touches = touches || c->contact_normal_force(network.impedance_input(i, x0)) > 0.0;
      }
    }
    if (settle && any_contact && !touches) {
      out.warn(t->get("settle"), *t, path + ".settle",
               "no point of '" + (*t)["body"].value_or(std::string{}) +
                   "' touches this surface at t = 0, so settle does nothing and the body drops "
                   "(settle places a body that lies on the surface, within 1 um)");
    }
    const auto threshold = number_of(t->get("stick_threshold"));
    if (threshold && speed_scale > 0.0 && *threshold > speed_scale) {
      out.warn(t->get("stick_threshold"), *t, path + ".stick_threshold",
               number_text(*threshold) + " is above every speed of the scene at t = 0 (at most " +
                   number_text(speed_scale) + "): its slips are reported as sticks");
    }
  }
}

// The size a body's penetration is measured against: a sphere's or cylinder's radius (a coin's
// half thickness if smaller), a box's smallest half edge; 0 where the body has no shape.
double body_size(const toml::table& doc, const std::string& name) {
  const toml::table* t = doc["bodies"][name].as_table();
  if (t == nullptr) return 0.0;
  const std::string shape = (*t)["shape"].value_or(std::string{});
  const double radius = number_of(t->get("radius")).value_or(0.0);
  if (shape == "sphere" || shape == "hollow_sphere") return radius;
  if (shape == "cylinder") return std::min(radius, 0.5 * number_of(t->get("length")).value_or(0.0));
  if (shape == "box") {
    if (const auto size = vec3_of(t->get("size"))) return 0.5 * size->minCoeff();
  }
  return 0.0;
}

// Bodies that start inside a surface or inside each other. The depth is read off the contact's
// own normal force at t = 0 (N = K d when the body starts without a normal speed), so it is the
// penetration the law sees, for every kind of contact point, rim and pair. Warned at the key
// that places the body (its `position`), once per contact table.
void check_start_penetration(const Scene& scene, Collector& out) {
  core::Network& network = *scene.network;
  const core::Vec x0 = network.initial_state();
  const toml::table& doc = scene.document;
  const auto by_table = elements_by_table(network);
  for (const auto& [path, t] : components(doc, "impedances")) {
    if (type_of(*t) != "kikuuwe_contact") continue;
    const auto found = by_table.find(path.substr(path.find('.') + 1));
    if (found == by_table.end()) continue;
    double depth = 0.0;
    for (const int i : found->second) {
      const core::Capabilities& c = network.capabilities(i);
      if (c.contact == nullptr || c.stiffness == nullptr || !(c.stiffness->stiffness() > 0.0))
        continue;
      depth = std::max(depth, c.contact->contact_normal_force(network.impedance_input(i, x0)) /
                                  c.stiffness->stiffness());
    }
    const std::string body = (*t)["body"].value_or(std::string{});
    const std::string other = (*t)["other"].value_or(std::string{});
    double size = body_size(doc, body);
    if (const double s = body_size(doc, other); s > 0.0) size = size > 0.0 ? std::min(size, s) : s;
    if (!(size > 0.0)) size = number_of(t->get("radius")).value_or(0.0);
    if (!(size > 0.0) || !(depth > kMaxStartPenetration * size)) continue;
    const toml::table* placed = doc["bodies"][body].as_table();
    const std::string what = other.empty() ? "the surface of " + path : "'" + other + "'";
    const std::string text = "'" + body + "' starts " + number_text(depth) + " m inside " + what +
                             ", more than " + number_text(100.0 * kMaxStartPenetration) +
                             "% of its size (" + number_text(size) +
                             " m): the contact's spring launches it at t = 0 (place it on the "
                             "surface, or use settle = true to start at rest)";
    if (placed != nullptr) {
      out.warn(placed->get("position"), *placed, "bodies." + body + ".position", text);
    } else {
      out.warn(nullptr, *t, path, text);
    }
  }
}

}  // namespace

std::vector<Warning> plausibility_warnings(const Scene& scene) {
  Collector out(scene);
  check_simulation(scene, out);
  check_gravity_and_contacts(scene, out);
  check_densities(scene.document, out);
  check_angles(scene.document, out);
  check_network(scene, out);
  check_start_penetration(scene, out);
  return out.take();
}

std::string format_warning(const Warning& w) {
  return sys::terminal_safe(w.file + ":" + std::to_string(w.line) + ":" +
                            std::to_string(w.column) + ": warning: " + w.text);
}

}  // namespace stiction::scene
