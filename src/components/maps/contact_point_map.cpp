#include "components/maps/contact_point_map.hpp"

#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/impedance/kikuuwe_contact.hpp"

namespace stiction::components {
namespace {

// Psi, Kikuuwe's contact law and Phi with every call direct (final classes, inline hot
// paths): the compiler keeps x_hat and u in registers (core/coupling.hpp). The capturing
// twin (kCapture) also stores x_hat and e for the run loop's slip observation; the plain one
// has no trace of it.
template <typename BodyType, bool kCapture = false>
class KikuuweContactCoupling final : public core::Coupling {
 public:
  KikuuweContactCoupling(const ContactPointMap& map, const BodyType& body,
                         const KikuuweContact& contact, const core::Slot& state,
                         double* motion_out = nullptr, double* state_out = nullptr)
      : map_(map),
        body_(body),
        contact_(contact),
        state_(state),
        motion_out_(motion_out),
        state_out_(state_out) {}

  // Flattened: every call below is inlined, the contact law included (left to itself the
  // compiler kept KikuuweContact::evaluate out of line, with x_hat, u and e's rate passed
  // through Eigen::Ref objects on the stack).
  [[gnu::flatten]] void exchange(double t, const double* x, double tau, double* x_dot,
                                 double* u_hat) override {
    Eigen::Matrix<double, 6, 1> x_hat;
    Eigen::Vector3d u;
    const core::BodyMotion at = map_.motion_of(body_, x, x_hat);
    if constexpr (kCapture) {
      for (int k = 0; k < 6; ++k) motion_out_[k] = x_hat[k];
      for (int k = 0; k < 2; ++k) state_out_[k] = x[state_.state_offset + k];
    }
    contact_.evaluate(t, x_hat,
                      Eigen::Map<const core::Vec>(x + state_.state_offset, state_.state_size), tau,
                      u, Eigen::Map<core::Vec>(x_dot + state_.state_offset, state_.state_size));
    map_.apply_to(body_, at, u, u_hat);
  }
  std::unique_ptr<core::Coupling> capturing(double* motion_out, double* state_out) const override {
    return std::make_unique<KikuuweContactCoupling<BodyType, true>>(map_, body_, contact_, state_,
                                                                    motion_out, state_out);
  }

 private:
  const ContactPointMap& map_;
  const BodyType& body_;
  const KikuuweContact& contact_;
  core::Slot state_;
  double* motion_out_;
  double* state_out_;
};

}  // namespace

ContactPointMap::ContactPointMap(const core::Body& body, double radius, const core::Vec3& normal,
                                 const core::Vec3& local)
    : body_(body),
      offset_(-radius * normal.normalized()),
      local_(local),
      body_point_(local != core::Vec3::Zero()) {}

std::unique_ptr<core::Coupling> ContactPointMap::direct_coupling(const core::Impedance& impedance,
                                                                 const core::Slot& state) const {
  const auto* contact = dynamic_cast<const KikuuweContact*>(&impedance);
  // The fused couplings carry [p_c, v_c] only: a body-fixed friction axis takes the generic path.
  if (contact == nullptr || carries_axis_ || contact->input_size() != 6) return nullptr;
  if (const auto* body = dynamic_cast<const RigidBody*>(&body_)) {
    return std::make_unique<KikuuweContactCoupling<RigidBody>>(*this, *body, *contact, state);
  }
  if (const auto* body = dynamic_cast<const PointMass*>(&body_)) {
    return std::make_unique<KikuuweContactCoupling<PointMass>>(*this, *body, *contact, state);
  }
  return nullptr;
}

}  // namespace stiction::components
