#include "components/impedance/torque_source.hpp"

#include <stdexcept>

namespace stiction::components {

namespace {

std::vector<TorqueSource::StateProfile> of_time(std::vector<TorqueSource::Profile> profiles) {
  std::vector<TorqueSource::StateProfile> out;
  for (auto& p : profiles) {
    out.emplace_back([p = std::move(p)](double t, const double* /*observed*/) { return p(t); });
  }
  return out;
}

}  // namespace

TorqueSource::TorqueSource(std::string name, std::vector<Profile> profiles, std::string signal_name)
    : TorqueSource(std::move(name), of_time(std::move(profiles)), 0, std::move(signal_name),
                   "torque_source") {}

TorqueSource::TorqueSource(std::string name, std::vector<StateProfile> profiles, int observed,
                           std::string signal_name, std::string type, Observer observer)
    : Impedance(std::move(name)),
      profiles_(std::move(profiles)),
      observed_(observed),
      observer_(std::move(observer)),
      signal_name_(std::move(signal_name)),
      type_(std::move(type)) {
  if (profiles_.empty() || observed_ < 0) {
    throw std::invalid_argument("source '" + this->name() + "': needs at least one entry");
  }
}

void TorqueSource::evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef /*y*/, double tau,
                            core::VecRef u, core::VecRef /*y_dot*/) const {
  const double* observed = x_hat.data() + 2 * size();
  if (observer_) observed = observer_(t, tau, observed);
  for (int i = 0; i < size(); ++i) u[i] = -profiles_[i](t, observed);
}

std::vector<core::SignalInfo> TorqueSource::signals() const {
  const bool force = type_ == "force_source";
  const std::string unit = force ? "N" : "N·m";
  const std::string description =
      force ? "prescribed force applied to the body (in the frame its scene entry names)"
            : "prescribed torque applied to the driven side";
  if (size() == 1) {
    return {{.name = signal_name_, .unit = unit, .frame = "joint", .description = description}};
  }
  return {{.name = signal_name_, .axes = size() == 3 ? core::xyz_axes() : core::index_axes(size()),
           .unit = unit, .frame = force ? "" : "world", .description = description}};
}

void TorqueSource::write_signals(core::ConstVecRef /*x_hat*/, core::ConstVecRef /*y*/,
                                 core::ConstVecRef u, core::VecRef out) const {
  out.head(u.size()) = -u;
}

}  // namespace stiction::components
