#include "python_impedance.hpp"

#include <pybind11/numpy.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/capabilities.hpp"
#include "python_callbacks.hpp"
#include "scene/components.hpp"

namespace stiction::python {

namespace {

// The largest size an element may state: far above any wiring (2 or 6 inputs, 1 or 3
// outputs) or any state a Python element steps at a useful speed.
constexpr long long kMaxElementSize = 1'000'000;

// A size the object states (an attribute or a property): an int in 0..kMaxElementSize
// (an int too large for C++ was "Unable to cast Python instance to C++ type": issue 39,
// found by fuzz/fuzz_python.py).
int size_of(const py::object& element, const char* name, const std::string& where) {
  const py::object value = element.attr(name);
  int overflow = 0;
  const long long size =
      py::isinstance<py::int_>(value) ? PyLong_AsLongLongAndOverflow(value.ptr(), &overflow) : -1;
  if (PyErr_Occurred() != nullptr) PyErr_Clear();
  if (overflow != 0 || size < 0 || size > kMaxElementSize) {
    throw std::invalid_argument(where + "." + name + " must be an int in 0.." +
                                std::to_string(kMaxElementSize) + ", got " + value_text(value));
  }
  return static_cast<int>(size);
}

// An array of n doubles owned by the element, handed to Python read-only: a callback that
// keeps it sees the next call's values, never freed memory.
py::array_t<double> input_array(int n, double*& data) {
  py::array_t<double> a(n);
  data = a.mutable_data();
  std::fill(data, data + n, 0.0);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Always an EnergyStore: an element without stored_energy() holds none (0 J), as a bundled
// element without the capability; with it, the energy monitor sees what a spring in Python
// holds, instead of taking its release for an instability.
// A state label or signal name becomes a column NAME.LABEL: a comma, quote or newline in it
// would break trajectory.csv's header (issue 39).
void require_column_name(const std::string& name, const std::string& where) {
  if (const std::string why = scene::signal_name_problem(name); !why.empty()) {
    throw std::invalid_argument(where + ": '" + name + "': " + why);
  }
}

class PythonImpedance : public core::Impedance, public core::EnergyStore {
 public:
  PythonImpedance(const std::string& name, py::object element)
      : Impedance(name), held_(std::make_unique<Held>()) {
    const std::string where = "the element '" + name + "' (" +
                              std::string(py::str(py::type::of(element).attr("__name__"))) + ")";
    type_ = py::str(py::type::of(element).attr("__name__"));
    in_ = size_of(element, "input_size", where);
    out_ = size_of(element, "output_size", where);
    state_ = size_of(element, "state_size", where);
    held_->evaluate = element.attr("evaluate");
    if (py::hasattr(element, "state_labels")) {
      for (const auto& label : element.attr("state_labels")) labels_.push_back(py::str(label));
      if (static_cast<int>(labels_.size()) != state_) {
        throw std::invalid_argument(where + ".state_labels names " +
                                    std::to_string(labels_.size()) + " entries, state_size is " +
                                    std::to_string(state_));
      }
      for (const std::string& label : labels_) require_column_name(label, where + ".state_labels");
    }
    initial_.assign(static_cast<std::size_t>(state_), 0.0);
    if (py::hasattr(element, "initial_state") && state_ > 0) {
      read_values(element.attr("initial_state")(), initial_.data(), state_,
                  where + ".initial_state() returned");
    }
    const py::object signals = py::getattr(element, "signals", py::none());
    if (!signals.is_none()) {
      if (!py::hasattr(element, "write_signals")) {
        throw std::invalid_argument(where + " defines signals() but not write_signals()");
      }
      held_->write_signals = element.attr("write_signals");
      // A method signals() or a plain list, as state_labels is.
      const py::object listed = PyCallable_Check(signals.ptr()) ? signals() : signals;
      for (const auto& item : listed) {
        core::SignalInfo s;
        if (py::isinstance<py::str>(item)) {
          s.name = py::str(item);
        } else {
          const auto entry = py::reinterpret_borrow<py::sequence>(item);
          if (entry.size() < 1 || entry.size() > 3) {
            throw std::invalid_argument(where +
                                        ".signals(): expected (name, unit) or (name, unit, "
                                        "description), got " +
                                        std::string(py::repr(item)));
          }
          s.name = py::str(entry[0]);
          if (entry.size() > 1) s.unit = py::str(entry[1]);
          if (entry.size() > 2) s.description = py::str(entry[2]);
        }
        require_column_name(s.name, where + ".signals()");
        signals_.push_back(std::move(s));
      }
    } else {
      core::SignalInfo u;
      u.name = "u";
      if (out_ == 3) u.axes = core::xyz_axes();
      if (out_ != 1 && out_ != 3) u.axes = core::index_axes(out_);
      u.description = "the element's output u (what the moving side exerts on it)";
      signals_.push_back(std::move(u));
    }
    if (py::hasattr(element, "slip_velocity")) held_->slip = element.attr("slip_velocity");
    // None (a subclass switching it off) counts as not defined.
    if (const py::object energy = py::getattr(element, "stored_energy", py::none());
        !energy.is_none())
      held_->energy = energy;
    held_->x = input_array(in_, x_);
    held_->y = input_array(state_, y_);
    held_->u = input_array(out_, u_);
    held_->element = std::move(element);
    what_ = "element '" + name + "'";
  }
  ~PythonImpedance() override {
    if (Py_IsInitialized() != 0) {
      py::gil_scoped_acquire gil;
      held_.reset();
    } else {
      static_cast<void>(held_.release());  // the interpreter is gone: nothing to release to
    }
  }

  std::string_view type() const override { return type_; }
  int input_size() const override { return in_; }
  int output_size() const override { return out_; }
  int state_size() const override { return state_; }
  std::vector<std::string> state_labels() const override { return labels_; }
  void initial_state(core::VecRef y) const override {
    for (int i = 0; i < state_; ++i) y[i] = initial_[static_cast<std::size_t>(i)];
  }

  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override {
    py::gil_scoped_acquire gil;
    copy_in(x_hat, y);
    const py::object result = held_->evaluate(t, held_->x, held_->y, tau);
    if (!py::isinstance<py::tuple>(result) && !py::isinstance<py::list>(result)) {
      raise(PyExc_TypeError, what_ + ": evaluate() returned " + std::string(py::repr(result)) +
                                 ", expected (u, y_dot)");
    }
    const auto pair = py::reinterpret_borrow<py::sequence>(result);
    if (pair.size() != 2) {
      raise(PyExc_TypeError, what_ + ": evaluate() returned " + std::to_string(pair.size()) +
                                 " items, expected (u, y_dot)");
    }
    read_values(pair[0], u.data(), out_, what_ + ": evaluate()'s u was");
    require_finite(u.data(), out_, "evaluate()'s u", t);
    const py::object rate = pair[1];
    if (state_ > 0 || !rate.is_none()) {
      read_values(rate, y_dot.data(), state_, what_ + ": evaluate()'s y_dot was");
      require_finite(y_dot.data(), state_, "evaluate()'s y_dot", t);
    }
  }

  std::vector<core::SignalInfo> signals() const override { return signals_; }
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override {
    if (!held_->write_signals) {
      out.head(out_) = u;
      return;
    }
    py::gil_scoped_acquire gil;
    copy_in(x_hat, y);
    std::memcpy(u_, u.data(), sizeof(double) * static_cast<std::size_t>(out_));
    read_values(held_->write_signals(held_->x, held_->y, held_->u), out.data(),
                static_cast<int>(signals_.size()), what_ + ": write_signals() returned");
  }

  // The Python stored_energy(x_hat, y) in J; 0 without one.
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override {
    if (!held_->energy) return 0.0;
    py::gil_scoped_acquire gil;
    copy_in(x_hat, y);
    double energy = 0.0;
    read_values(held_->energy(held_->x, held_->y), &energy, 1,
                what_ + ": stored_energy() returned");
    // A NaN energy would switch the energy monitor off for the whole network.
    require_finite(&energy, 1, "stored_energy()", std::nullopt);
    return energy;
  }

  // The Python slip_velocity(x_hat): a number (a joint's rate) or 3 numbers.
  core::Vec3 slip(core::ConstVecRef x_hat) const {
    py::gil_scoped_acquire gil;
    copy_in(x_hat, core::Vec());
    const py::object v = held_->slip(held_->x);
    core::Vec3 out = core::Vec3::Zero();
    // One number (a Python or NumPy scalar, or a 1-entry array) for a joint, else 3.
    const bool scalar = py::isinstance<py::array>(v)
                            ? py::reinterpret_borrow<py::array>(v).size() == 1
                            : PySequence_Check(v.ptr()) == 0 || py::len(v) == 1;
    read_values(v, out.data(), scalar ? 1 : 3, what_ + ": slip_velocity() returned");
    require_finite(out.data(), scalar ? 1 : 3, "slip_velocity()", std::nullopt);
    return out;
  }

 private:
  // A non-finite value from the element is the element's fault, named with its inputs
  // (issue 39): left to the run, it became a NaN state blamed on the step ("try dt = 3.9e-8")
  // or, from stored_energy(), an energy monitor switched off. Raised as ValueError.
  void require_finite(const double* values, int n, const char* what,
                      std::optional<double> t) const {
    for (int i = 0; i < n; ++i) {
      if (std::isfinite(values[i])) continue;
      std::ostringstream m;
      m.precision(6);
      m << what_ << ": " << what << " is not finite (" << values[i] << " at entry " << i << ")";
      if (t) m << " at t = " << *t << " s";
      m << ", for x_hat = [";
      for (int k = 0; k < in_; ++k) m << (k ? ", " : "") << x_[k];
      m << "]";
      if (state_ > 0) {
        m << ", y = [";
        for (int k = 0; k < state_; ++k) m << (k ? ", " : "") << y_[k];
        m << "]";
      }
      raise(PyExc_ValueError, m.str());
    }
  }

  void copy_in(core::ConstVecRef x_hat, core::ConstVecRef y) const {
    std::memcpy(x_, x_hat.data(), sizeof(double) * static_cast<std::size_t>(in_));
    if (y.size() == state_ && state_ > 0)
      std::memcpy(y_, y.data(), sizeof(double) * static_cast<std::size_t>(state_));
  }

  struct Held {
    py::object element, evaluate, write_signals, slip, energy;
    py::array_t<double> x, y, u;
  };
  std::unique_ptr<Held> held_;
  double *x_ = nullptr, *y_ = nullptr, *u_ = nullptr;  // the arrays' data
  int in_ = 0, out_ = 0, state_ = 0;
  std::string type_, what_;
  std::vector<std::string> labels_;
  std::vector<double> initial_;
  std::vector<core::SignalInfo> signals_;
};

// The capabilities are found by dynamic_cast (core/capabilities.hpp): one class per set.
class SlidingPythonImpedance final : public PythonImpedance, public core::SlipElement {
 public:
  using PythonImpedance::PythonImpedance;
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override { return slip(x_hat); }
};

class StiffPythonImpedance final : public PythonImpedance, public core::StiffnessHint {
 public:
  StiffPythonImpedance(const std::string& name, py::object element, double stiffness)
      : PythonImpedance(name, std::move(element)), StiffnessHint(stiffness) {}
};

class SlidingStiffPythonImpedance final : public PythonImpedance,
                                          public core::SlipElement,
                                          public core::StiffnessHint {
 public:
  SlidingStiffPythonImpedance(const std::string& name, py::object element, double stiffness)
      : PythonImpedance(name, std::move(element)), StiffnessHint(stiffness) {}
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override { return slip(x_hat); }
};

}  // namespace

std::unique_ptr<core::Impedance> make_python_impedance(const std::string& name,
                                                       py::object element) {
  // Read the capabilities first (the plain element checks everything else), then build the
  // class that has them.
  const bool slides = py::hasattr(element, "slip_velocity");
  const py::object stiffness = py::getattr(element, "stiffness", py::none());
  if (stiffness.is_none()) {
    if (slides) return std::make_unique<SlidingPythonImpedance>(name, std::move(element));
    return std::make_unique<PythonImpedance>(name, std::move(element));
  }
  double k = 0.0;
  try {
    k = stiffness.cast<double>();
  } catch (const py::cast_error&) {
    throw std::invalid_argument("the element '" + name + "'.stiffness must be a number, got " +
                                std::string(py::repr(stiffness)));
  }
  if (!(k > 0.0) || !std::isfinite(k)) {
    throw std::invalid_argument("the element '" + name + "'.stiffness must be a finite number > 0");
  }
  if (slides) return std::make_unique<SlidingStiffPythonImpedance>(name, std::move(element), k);
  return std::make_unique<StiffPythonImpedance>(name, std::move(element), k);
}

}  // namespace stiction::python
