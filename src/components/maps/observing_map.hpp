// A coordinate map that also observes, so that an element's law can depend on other
// components (feedback) without the core knowing: the network hands every map the whole
// stage state anyway. Phi is the inner map's: what is observed receives no force.
//
// Two kinds of observed value, each one signal entry (a CSV column such as "arm.theta.0"):
// - an admittance's signal, read from its state;
// - an impedance's signal (a contact's friction force "ground.f.x", a spring's force): the
//   impedance is evaluated at the stage. Its output depends on the stage time and step tau,
//   which a map does not see, so Psi only gathers what that evaluation needs (the observed
//   impedance's own x_hat, through its map, and its state y) and values() evaluates it when
//   the observing element is evaluated, with that element's t and tau.
// x_hat = [inner map's x_hat, one entry per observed admittance value, then per observed
// impedance its (x_hat, y)]. Only the impedances named are evaluated, once per stage each.
#pragma once

#include <memory>
#include <vector>

#include "core/coordinate_map.hpp"
#include "core/network.hpp"

namespace stiction::components {

class ObservingMap final : public core::CoordinateMap {
 public:
  struct Observed {
    const core::Admittance* admittance = nullptr;  // an admittance's signal entry, or
    const core::Impedance* impedance = nullptr;    // an impedance's, evaluated at the stage
    const core::CoordinateMap* map = nullptr;      // the impedance's own map (its Psi)
    int entry = 0;  // index into the component's signal entries (its CSV columns, in order)
  };
  ObservingMap(std::unique_ptr<core::CoordinateMap> inner, std::vector<Observed> observed);
  int motion_size() const override { return inner_->motion_size() + raw_size_; }
  int force_size() const override { return inner_->force_size(); }
  // The inner map's x_hat comes first, unchanged.
  int conjugate_velocity_offset() const override { return inner_->conjugate_velocity_offset(); }
  std::vector<const core::Admittance*> admittances() const override;
  void bind(const std::vector<core::Slot>& slots) override;
  // Where the observed impedances' states are: known once the network is finalized (the
  // network binds maps to admittances only). Call before the first motion().
  void locate(const core::Network& network);
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override {
    inner_->apply(x, u, u_hat);
  }

  // Entries of x_hat after the inner map's.
  int raw_size() const { return raw_size_; }
  // The observed values, in the order of observed(), from the raw part of an x_hat this map
  // wrote, at stage time t and step tau. Points into scratch valid until the next call.
  const double* values(double t, double tau, const double* raw) const;

  const core::CoordinateMap& inner() const { return *inner_; }
  const std::vector<Observed>& observed() const { return observed_; }

 private:
  struct BodySource {  // one observed admittance
    const core::Admittance* admittance;
    core::Slot slot;
    mutable core::Vec signals;  // scratch for its signal row, sized once
  };
  struct ElementSource {  // one observed impedance
    const core::Impedance* impedance;
    const core::CoordinateMap* map;
    int raw_offset;                       // where its x_hat, then its y, sit in the raw part
    int state_offset = -1;                // its y in the system state; -1 until locate()
    mutable core::Vec u, y_dot, signals;  // scratch for one evaluation, sized once
  };
  std::unique_ptr<core::CoordinateMap> inner_;
  std::vector<Observed> observed_;
  int inner_admittances_ = 0;
  int body_values_ = 0;  // raw entries 0..body_values_-1: the admittance values
  int raw_size_ = 0;
  std::vector<BodySource> bodies_;
  std::vector<ElementSource> elements_;
  std::vector<int> source_of_;  // per observed value: index into bodies_ or elements_
  std::vector<int> raw_of_;     // per observed value: its raw index (admittance values only)
  mutable core::Vec values_;
};

}  // namespace stiction::components
