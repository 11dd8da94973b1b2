// An input profile written as an expression (muParser syntax) of time t and, optionally, of
// named signals of the scene ("-20*(arm.theta.0 - 1) - 2*arm.omega.0", "-ground.f.x"). It is compiled once
// at load time; evaluate() then runs muParser's bytecode, which does not allocate, so a
// profile can be called inside every stage of a simulation step.
#pragma once

#include <toml++/toml.h>

#include <memory>
#include <string>
#include <vector>

#include "core/model_fault.hpp"
#include "scene/toml_reader.hpp"

namespace stiction::scene {

// An expression of t alone that gave a value that is not finite (1/0, log(0), sqrt(-1)) at a
// finite t, or an expression of the state that did at t = 0 with the scene's initial state:
// bad input at the expression (exit 2), with the time and the state's values. (One of the
// state that goes non-finite later is left to the run's instability monitors: the state may be
// a runaway's.) It passes through core::simulate (core::ModelFault) instead of becoming an
// instability.
class ExpressionValueError : public InputError, public core::ModelFault {
 public:
  explicit ExpressionValueError(const std::string& message) : InputError(message) {}
};

class Expression {
 public:
  // Compiles `text`. Errors are InputError at `where` (the TOML string value holding the
  // expression), the column moved to the offending character inside the expression.
  // `what` names the key in messages ("impedances.motor0.torque"). `signals` are the names
  // (CSV column names, e.g. "arm.theta.0") the expression may use besides t; a name that is
  // neither t, a constant, a function nor one of them is an error at its column.
  Expression(const std::string& text, const toml::source_region& where, const std::string& what,
             const std::vector<std::string>& signals = {});
  // Compiles without a source position (tests, command-line values): errors name column
  // positions inside the expression only.
  explicit Expression(const std::string& text, const std::vector<std::string>& signals = {});
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;

  const std::string& text() const { return text_; }
  // The signals the expression uses, in the order evaluate() takes their values.
  const std::vector<std::string>& used_signals() const { return used_; }
  // ExpressionValueError when the value is not finite while t is (evaluate(t) only).
  double evaluate(double t) const;
  // values[i] is the value of used_signals()[i]. ExpressionValueError when the value is not
  // finite at t = 0 while the values are (the initial state is the scene's own).
  double evaluate(double t, const double* values) const;
  // Evaluates an expression of t alone at t = 0, at the output rows' times k / output_rate
  // (up to 10001 of them, spread evenly over the run past that) and at t = duration:
  // ExpressionValueError at the first value that is not finite. An expression reading
  // signals is not checked (a non-finite value of it is the run's instability).
  void check_over(double duration, double output_rate) const;
  // Throws an InputError at the first place the expression names `signal` (one of
  // used_signals()): "KEY: why" for an expression that is well formed but cannot be wired.
  [[noreturn]] void fail_at(const std::string& signal, const std::string& why) const;

 private:
  // `values` (the used signals' values, or null) are named in the message.
  [[noreturn]] void fail_value(double t, double value, const double* values = nullptr) const;
  struct Impl;
  std::string text_;
  toml::source_region where_;
  std::string what_;
  std::vector<std::string> used_;
  std::unique_ptr<Impl> impl_;  // the parser keeps the addresses of its variables: keep them stable
};

}  // namespace stiction::scene
