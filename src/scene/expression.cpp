#include "scene/expression.hpp"

#include <cmath>

#include <muParser.h>

#include "scene/toml_reader.hpp"

namespace stiction::scene {

struct Expression::Impl {
  mu::Parser parser;
  double t = 0.0;  // bound to the variable "t" by address
};

namespace {

// The column of the opening quote is where toml++ places a string value; the expression
// text starts one character later (basic and literal strings alike).
toml::source_region inside(const toml::source_region& where, int position) {
  toml::source_region r = where;
  r.begin.column = static_cast<toml::source_index>(r.begin.column + 1 + position);
  return r;
}

}  // namespace

Expression::Expression(const std::string& text, const toml::source_region& where,
                       const std::string& what)
    : text_(text), impl_(std::make_unique<Impl>()) {
  try {
    impl_->parser.DefineVar("t", &impl_->t);
    impl_->parser.SetExpr(text_);
    // Eval compiles to bytecode (and reports most syntax errors); later calls reuse it.
    impl_->t = 0.0;
    impl_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    const int pos = std::max(0, static_cast<int>(e.GetPos()));
    std::string message = what + ": invalid expression \"" + text_ + "\": " + e.GetMsg() +
                          " (column " + std::to_string(pos + 1) + " of the expression)";
    throw InputError::at(inside(where, pos), message);
  }
}

Expression::Expression(const std::string& text)
    : Expression(text, toml::source_region{}, "expression") {}

Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::evaluate(double t) const {
  impl_->t = t;
  return impl_->parser.Eval();
}

}  // namespace stiction::scene
