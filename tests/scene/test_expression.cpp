#include <cmath>

#include <catch2/catch.hpp>

#include "scene/expression.hpp"
#include "scene/toml_reader.hpp"

using stiction::scene::Expression;
using stiction::scene::InputError;

TEST_CASE("expression: the paper's motor torque (28c) piecewise in t") {
  Expression e("t < 4 ? min(0.52, 0.3*t) : 0.336 + 0.144*sin(100*t)");
  CHECK(e.evaluate(0.0) == 0.0);
  CHECK(e.evaluate(1.0) == Approx(0.3));
  CHECK(e.evaluate(3.0) == Approx(0.52));
  CHECK(e.evaluate(5.0) == Approx(0.336 + 0.144 * std::sin(500.0)));
  // Evaluation is repeatable (bytecode reused, t rebound each call).
  CHECK(e.evaluate(1.0) == Approx(0.3));
}

TEST_CASE("expression: survives a move (the parser keeps the address of t)") {
  Expression a("max(t, 2) + cos(t)");
  Expression b = std::move(a);
  CHECK(b.evaluate(3.0) == Approx(3.0 + std::cos(3.0)));
  CHECK(b.evaluate(0.0) == Approx(3.0));
}

TEST_CASE("expression: a malformed expression names the column inside the value") {
  toml::source_region where;
  where.begin = {7, 10};  // the opening quote of the string value
  where.path = std::make_shared<const std::string>("scene.toml");
  try {
    Expression e("0.3*t + * 2", where, "impedances.motor0.torque");
    FAIL("no error for a malformed expression");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.rfind("scene.toml:7:", 0) == 0);
    CHECK(message.find("error: impedances.motor0.torque") != std::string::npos);
    CHECK(message.find("of the expression") != std::string::npos);
    // The error is at or after the offending '*' (column 7 of the expression, 10 + 1 + 6).
    const int column = std::stoi(message.substr(std::string("scene.toml:7:").size()));
    CHECK(column >= 17);
  }
}

TEST_CASE("expression: only t is a variable") {
  CHECK_THROWS_AS(Expression("x + t"), InputError);
  CHECK_THROWS_AS(Expression("sin(t"), InputError);
  CHECK_THROWS_AS(Expression(""), InputError);
}
