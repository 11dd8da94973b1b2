// `settle = true` on a contact: the body starts in static equilibrium with its contacts
// under its own weight, instead of dropping onto them. The points of its settling contacts
// that touch (penetration >= -1 um, within the surface's extent) are springs of stiffness K
// along the normal and Kt in the surface plane, all stuck; the body is moved by the small
// translation and rotation that balances gravity (a few Newton steps on the 6x6 stiffness
// of those springs, least-norm where it is singular, e.g. a sphere's free rolling), and each
// touching point's friction state e is set to the tangential deflection it then carries.
// Only gravity is balanced: springs, sources and other contacts are not part of it. Where
// friction cannot hold the load (mu too small), the body is still placed so, and slides.
#pragma once

#include <functional>
#include <vector>

#include "components/impedance/contact_law.hpp"
#include "components/impedance/surface_extent.hpp"
#include "core/admittance.hpp"
#include "core/types.hpp"

namespace stiction::scene {

struct SettlePoint {
  core::Vec3 local = core::Vec3::Zero();   // body frame
  double radius = 0.0;                     // contact sphere about `local`
  components::ContactFrame frame;          // the surface at t = 0
  core::Vec3 origin = core::Vec3::Zero();  // a point of the plane at t = 0
  // Whether a world point lies within the surface's extent at t = 0.
  std::function<bool(const core::Vec3&)> inside;
  double k = 0.0, kt = 0.0;
  std::function<void(const Eigen::Vector2d&)> set_e;  // the element's initial friction state
};

struct SettleBody {
  core::Admittance* body = nullptr;  // a point mass or a rigid body
  std::vector<SettlePoint> points;
};

// Moves `b.body`'s initial pose and sets the touching points' e (see above).
void settle(const SettleBody& b, const core::Vec3& gravity);

}  // namespace stiction::scene
