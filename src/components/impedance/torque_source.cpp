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
  const std::string description = "prescribed torque applied to the driven side";
  if (profiles_.size() == 1) {
    return {{.name = signal_name_, .unit = "N·m", .frame = "joint", .description = description}};
  }
  const int n = static_cast<int>(profiles_.size());
  return {{.name = signal_name_, .axes = n == 3 ? core::xyz_axes() : core::index_axes(n),
           .unit = "N·m", .frame = "world", .description = description}};
}

void TorqueSource::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                                 core::ConstVecRef u, core::VecRef out) const {
  out.head(u.size()) = -u;
}

}  // namespace stiction::components
