#include "scene/urdf_numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <vector>

#include "scene/urdf_loader.hpp"

namespace stiction::scene {
namespace {

struct NumericAttribute {
  const char* element;
  const char* attribute;
  int count;         // numbers in the attribute
  bool mass = false;  // bounded by kMaxUrdfMass
};

// URDF's numeric attributes (http://wiki.ros.org/urdf/XML).
constexpr NumericAttribute kAttributes[] = {
    {"origin", "xyz", 3},         {"origin", "rpy", 3},
    {"axis", "xyz", 3},           {"mass", "value", 1, true},
    {"inertia", "ixx", 1, true},  {"inertia", "ixy", 1, true},
    {"inertia", "ixz", 1, true},  {"inertia", "iyy", 1, true},
    {"inertia", "iyz", 1, true},  {"inertia", "izz", 1, true},
    {"limit", "lower", 1},        {"limit", "upper", 1},
    {"limit", "effort", 1},       {"limit", "velocity", 1},
    {"dynamics", "damping", 1},   {"dynamics", "friction", 1},
    {"safety_controller", "soft_lower_limit", 1},
    {"safety_controller", "soft_upper_limit", 1},
    {"safety_controller", "k_position", 1},
    {"safety_controller", "k_velocity", 1},
    {"calibration", "rising", 1}, {"calibration", "falling", 1},
    {"box", "size", 3},           {"cylinder", "radius", 1},
    {"cylinder", "length", 1},    {"sphere", "radius", 1},
    {"mesh", "scale", 3},         {"color", "rgba", 4},
};

// 'token' (built by appending: GCC 12 warns falsely on "'" + std::string(...)).
std::string quoted(std::string_view token) {
  std::string q(1, '\'');
  q.append(token);
  q += '\'';
  return q;
}

// Why `text` is not `count` finite numbers (at most kMaxUrdfMass in magnitude for a mass), or
// empty.
std::string why_not_numbers(std::string_view text, int count, bool mass) {
  int found = 0;
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && std::strchr(" \t\r\n", text[i]) != nullptr) ++i;
    if (i == text.size()) break;
    std::size_t end = i;
    while (end < text.size() && std::strchr(" \t\r\n", text[end]) == nullptr) ++end;
    const std::string_view token = text.substr(i, end - i);
    double value = 0.0;
    // from_chars takes no leading '+', which URDF exporters may write ("+0.5").
    const std::string_view digits = token.size() > 1 && token[0] == '+' ? token.substr(1) : token;
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || ptr != digits.data() + digits.size()) {
      return quoted(token) + " is not a number (a decimal point, not a comma)";
    }
    if (!std::isfinite(value)) return quoted(token) + " is not finite";
    if (mass && std::abs(value) > kMaxUrdfMass) {
      return quoted(token) + " is above 1e12 (kg, kg m^2): it would overflow the dynamics";
    }
    ++found;
    i = end;
  }
  if (found != count) {
    return "has " + std::to_string(found) + " number(s), " + std::to_string(count) + " expected";
  }
  return {};
}

}  // namespace

void check_urdf_numbers(const TiXmlDocument& xml, const std::string& origin) {
  // An explicit stack: a document nested thousands of levels deep must not overflow ours.
  std::vector<const TiXmlElement*> stack;
  if (const TiXmlElement* root = xml.RootElement()) stack.push_back(root);
  while (!stack.empty()) {
    const TiXmlElement* e = stack.back();
    stack.pop_back();
    for (const NumericAttribute& a : kAttributes) {
      if (std::strcmp(e->Value(), a.element) != 0) continue;
      const char* text = e->Attribute(a.attribute);
      if (text == nullptr) continue;
      if (const std::string why = why_not_numbers(text, a.count, a.mass); !why.empty()) {
        throw UrdfError(origin + ":" + std::to_string(e->Row()) + ":" + std::to_string(e->Column()) +
                        ": <" + a.element + "> " + a.attribute + "=\"" + text + "\": " + why);
      }
    }
    for (const TiXmlElement* child = e->FirstChildElement(); child != nullptr;
         child = child->NextSiblingElement()) {
      stack.push_back(child);
    }
  }
}

}  // namespace stiction::scene
