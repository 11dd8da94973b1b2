#include "components/impedance/torque_source.hpp"

namespace stiction::components {

TorqueSource::TorqueSource(std::string name, std::vector<Profile> profiles,
                           std::string signal_name)
    : Impedance(std::move(name)),
      profiles_(std::move(profiles)),
      signal_name_(std::move(signal_name)) {}

void TorqueSource::evaluate(double t, core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                            double /*tau*/, core::VecRef u, core::VecRef /*y_dot*/) const {
  for (std::size_t i = 0; i < profiles_.size(); ++i) u[i] = -profiles_[i](t);
}

std::vector<core::SignalInfo> TorqueSource::signals() const {
  if (profiles_.size() == 1) return {{signal_name_, {}}};
  const int n = static_cast<int>(profiles_.size());
  return {{signal_name_, n == 3 ? core::xyz_axes() : core::index_axes(n)}};
}

void TorqueSource::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                                 core::ConstVecRef u, core::VecRef out) const {
  out.head(u.size()) = -u;
}

}  // namespace stiction::components
