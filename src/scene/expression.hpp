// An input profile written as an expression of time t (muParser syntax, e.g.
// "t < 4 ? min(0.52, 0.3*t) : 0.336 + 0.144*sin(100*t)"). It is compiled once at load
// time; evaluate() then runs muParser's bytecode, which does not allocate, so a profile can
// be called inside a simulation step.
#pragma once

#include <memory>
#include <string>

#include <toml++/toml.h>

namespace stiction::scene {

class Expression {
 public:
  // Compiles `text`. Errors are InputError at `where` (the TOML string value holding the
  // expression), the column moved to the offending character inside the expression.
  // `what` names the key in messages ("impedances.motor0.torque").
  Expression(const std::string& text, const toml::source_region& where, const std::string& what);
  // Compiles without a source position (tests, command-line values): errors name column
  // positions inside the expression only.
  explicit Expression(const std::string& text);
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;

  const std::string& text() const { return text_; }
  double evaluate(double t) const;

 private:
  struct Impl;
  std::string text_;
  std::unique_ptr<Impl> impl_;  // the parser keeps the address of t: keep it stable on moves
};

}  // namespace stiction::scene
