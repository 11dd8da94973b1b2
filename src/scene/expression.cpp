#include "scene/expression.hpp"

#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "scene/toml_reader.hpp"

namespace stiction::scene {

struct Expression::Impl {
  mu::Parser parser;
  double t = 0.0;              // bound to the variable "t" by address
  std::vector<double> values;  // bound to the used signals by address; sized once
};

namespace {

// Signal names are dotted ("arm.theta.0"): muParser's name characters plus '.'. Not '-':
// it is the minus operator (a component named with '-' cannot be used in an expression).
constexpr const char* kNameChars =
    "0123456789_.abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";

// The column of the opening quote is where toml++ places a string value; the expression
// text starts one character later (basic and literal strings alike).
toml::source_region inside(const toml::source_region& where, int position) {
  toml::source_region r = where;
  r.begin.column = static_cast<toml::source_index>(r.begin.column + 1 + position);
  return r;
}

bool looks_like_name(const std::string& token) {
  return !token.empty() && (std::isalpha(static_cast<unsigned char>(token[0])) || token[0] == '_');
}

std::string unknown_name_message(const std::string& token,
                                 const std::vector<std::string>& signals) {
  std::string message = "unknown name '" + token + "': an expression may use t";
  if (signals.empty()) return message + " only";
  // Suggest the signals of the component the name starts with, if any.
  const std::string component = token.substr(0, token.find('.'));
  std::string same;
  int shown = 0;
  for (const auto& s : signals) {
    if (s.rfind(component + ".", 0) == 0 && shown < 16) {
      same += (same.empty() ? "" : ", ") + s;
      ++shown;
    }
  }
  message += " and the scene's signals by their CSV column names";
  if (!same.empty()) return message + " (" + component + " has: " + same + ")";
  return message + " (e.g. " + signals.front() + ")";
}

// The column of the first assignment operator (=, +=, -=, *=, /=) or -1: muParser assigns to
// a variable ("t=5" sets t and gives 5), which a profile must never do. '=' belongs to a
// comparison when it follows '=', '<', '>' or '!' or precedes '='.
int assignment_position(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '=') continue;
    const char before = i > 0 ? text[i - 1] : ' ';
    const char after = i + 1 < text.size() ? text[i + 1] : ' ';
    if (after == '=') {
      ++i;  // "==": skip both
      continue;
    }
    if (before == '<' || before == '>' || before == '!') continue;
    const bool compound = before == '+' || before == '-' || before == '*' || before == '/';
    return static_cast<int>(compound ? i - 1 : i);
  }
  return -1;
}

// The column of the first ',' outside parentheses (a list of expressions, "1,2"), or -1.
int top_level_comma(const std::string& text) {
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '(') ++depth;
    if (text[i] == ')') --depth;
    if (text[i] == ',' && depth <= 0) return static_cast<int>(i);
  }
  return -1;
}

std::string number_text(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

}  // namespace

Expression::Expression(const std::string& text, const toml::source_region& where,
                       const std::string& what, const std::vector<std::string>& signals)
    : text_(text), where_(where), what_(what), impl_(std::make_unique<Impl>()) {
  auto fail = [&](const mu::Parser::exception_type& e) {
    const int pos = std::max(0, static_cast<int>(e.GetPos()));
    const std::string token = e.GetToken();
    std::string detail = e.GetMsg();
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN && looks_like_name(token)) {
      detail = unknown_name_message(token, signals);
    }
    throw InputError::at(inside(where, pos), what + ": invalid expression \"" + text_ +
                                                 "\": " + detail + " (column " +
                                                 std::to_string(pos + 1) + " of the expression)");
  };
  // One expression, nothing assigned: muParser also accepts "t=5" and "1,2" (issue 25).
  const auto refuse = [&](int pos, const std::string& why) {
    throw InputError::at(inside(where, pos), what + ": invalid expression \"" + text_ + "\": " + why +
                                                 " (column " + std::to_string(pos + 1) +
                                                 " of the expression)");
  };
  if (const int pos = assignment_position(text_); pos >= 0) {
    refuse(pos, "an assignment ('=', '+=', ...) is not an expression (a comparison is '==')");
  }
  if (const int pos = top_level_comma(text_); pos >= 0) {
    refuse(pos, "a list of expressions separated by ',': give exactly one");
  }
  // First pass: every signal is a variable, to learn which ones the expression uses (and
  // to report syntax errors and unknown names with their column).
  try {
    mu::Parser probe;
    probe.DefineNameChars(kNameChars);
    double dummy = 0.0;
    probe.DefineVar("t", &dummy);
    for (const auto& s : signals) {
      // A name muParser cannot spell (a component named with '-') cannot be used.
      if (s.find_first_not_of(kNameChars) == std::string::npos) probe.DefineVar(s, &dummy);
    }
    probe.SetExpr(text_);
    probe.Eval();
    for (const auto& [name, address] : probe.GetUsedVar()) {
      if (name != "t") used_.push_back(name);
    }
  } catch (const mu::Parser::exception_type& e) {
    fail(e);
  }
  // The parser that runs: t and the used signals only, bound to storage sized once.
  std::sort(used_.begin(), used_.end());
  impl_->values.assign(used_.size(), 0.0);
  try {
    impl_->parser.DefineNameChars(kNameChars);
    impl_->parser.DefineVar("t", &impl_->t);
    for (std::size_t i = 0; i < used_.size(); ++i)
      impl_->parser.DefineVar(used_[i], &impl_->values[i]);
    impl_->parser.SetExpr(text_);
    // Eval compiles to bytecode; later calls reuse it.
    impl_->t = 0.0;
    impl_->parser.Eval();
    if (impl_->parser.GetNumResults() != 1) {
      refuse(0, "it gives " + std::to_string(impl_->parser.GetNumResults()) +
                    " values: give exactly one expression");
    }
  } catch (const mu::Parser::exception_type& e) {
    fail(e);
  }
}

Expression::Expression(const std::string& text, const std::vector<std::string>& signals)
    : Expression(text, toml::source_region{}, "expression", signals) {}

Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

void Expression::fail_at(const std::string& signal, const std::string& why) const {
  // The first occurrence of the name as a whole token (not inside a longer name).
  const std::string chars = kNameChars;
  std::size_t pos = text_.find(signal);
  while (pos != std::string::npos) {
    const std::size_t end = pos + signal.size();
    const bool starts = pos == 0 || chars.find(text_[pos - 1]) == std::string::npos;
    const bool ends = end == text_.size() || chars.find(text_[end]) == std::string::npos;
    if (starts && ends) break;
    pos = text_.find(signal, pos + 1);
  }
  const int column = pos == std::string::npos ? 0 : static_cast<int>(pos);
  throw InputError::at(inside(where_, column), what_ + ": " + why);
}

void Expression::fail_value(double t, double value, const double* values) const {
  std::string inputs = "t = " + number_text(t) + " s";
  if (values != nullptr) {
    // The values it saw: the initial state's, or the step check's perturbation of them.
    inputs += " with ";
    for (std::size_t i = 0; i < used_.size(); ++i)
      inputs += (i == 0 ? "" : ", ") + used_[i] + " = " + number_text(values[i]);
    inputs += " (the start of the run)";
  }
  throw ExpressionValueError(
      InputError::at(inside(where_, 0), what_ + ": the expression \"" + text_ + "\" is " +
                                            number_text(value) + " at " + inputs +
                                            ": an expression must give a finite number over the "
                                            "whole run (the expression's fault, not the step's)")
          .what());
}

double Expression::evaluate(double t) const {
  impl_->t = t;
  const double v = impl_->parser.Eval();
  if (!std::isfinite(v) && std::isfinite(t)) fail_value(t, v);
  return v;
}

double Expression::evaluate(double t, const double* values) const {
  impl_->t = t;
  std::copy(values, values + impl_->values.size(), impl_->values.begin());
  // An expression of the state that goes non-finite at a finite but wild state (a runaway, an
  // implicit integrator's Newton trial) is the run's instability, which the run's monitors
  // report (exit 3) and the implicit integrator answers by halving its step. At t = 0 the
  // state is the scene's own initial state (or the step check's tiny perturbations of it),
  // which no integrator has touched: a value that is not finite there is the expression's
  // fault, as for an expression of t alone.
  const double v = impl_->parser.Eval();
  if (!std::isfinite(v) && t == 0.0 &&
      std::all_of(values, values + impl_->values.size(), [](double x) { return std::isfinite(x); }))
    fail_value(t, v, values);
  return v;
}

void Expression::check_over(double duration, double output_rate) const {
  if (!used_.empty()) return;
  constexpr double kMaxSamples = 10001.0;
  const double rows = std::floor(duration * output_rate + 1e-9) + 1.0;
  if (rows <= kMaxSamples) {
    for (long k = 0; k < static_cast<long>(rows); ++k) evaluate(static_cast<double>(k) / output_rate);
  } else {
    for (long k = 0; k < static_cast<long>(kMaxSamples); ++k)
      evaluate(duration * static_cast<double>(k) / (kMaxSamples - 1.0));
  }
  evaluate(duration);
}

}  // namespace stiction::scene
