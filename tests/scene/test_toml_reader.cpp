#include <catch2/catch.hpp>

#include "scene/toml_reader.hpp"

using namespace stiction::scene;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {
toml::table parse(const char* text) { return toml::parse(std::string_view(text), std::string_view("t.toml")); }
}  // namespace

TEST_CASE("toml_reader: typed reads with defaults") {
  const toml::table doc = parse("a = 1\nb = 2.5\ns = \"x\"\nv = [1, 2, 3.5]\nflag = true\n");
  TableReader r(doc, "");
  CHECK(r.number("a", 0.0) == 1.0);  // integers are numbers
  CHECK(r.positive("b", 1.0) == 2.5);
  CHECK(r.number("missing", 7.0) == 7.0);
  CHECK(r.string("s", "") == "x");
  CHECK(r.vec3("v", {}) == stiction::core::Vec3(1, 2, 3.5));
  CHECK(r.boolean("flag", false));
  CHECK_NOTHROW(r.finish());
}

TEST_CASE("toml_reader: an unread key is an error at its position") {
  const toml::table doc = parse("[body]\nmass = 1\nmas = 2\n");
  TableReader root(doc, "");
  auto body = root.subtable("body");
  REQUIRE(body);
  body->number("mass", 0.0);
  CHECK_THROWS_WITH(body->finish(), StartsWith("t.toml:3:1: error: unknown key 'body.mas'"));
}

TEST_CASE("toml_reader: range and type errors name the key at its value") {
  const toml::table doc = parse("mass = -1\nname = 3\nv = [1, 2]\n");
  TableReader r(doc, "bodies.ball");
  CHECK_THROWS_WITH(r.positive("mass", 1.0), StartsWith("t.toml:1:8: error: bodies.ball.mass: must be > 0"));
  CHECK_THROWS_WITH(r.string("name", ""), Contains("bodies.ball.name: expected a string"));
  CHECK_THROWS_WITH(r.vec3("v", {}), Contains("expected 3 numbers"));
  CHECK_THROWS_WITH(r.required_number("absent"), Contains("bodies.ball.absent: missing"));
}

TEST_CASE("toml_reader: arrays of tables carry their index in messages") {
  const toml::table doc = parse("links = [{length = 1}, {length = \"x\"}]\n");
  TableReader r(doc, "arm");
  auto links = r.array_of_tables("links");
  REQUIRE(links.size() == 2);
  CHECK(links[0].number("length", 0.0) == 1.0);
  CHECK_THROWS_WITH(links[1].number("length", 0.0), Contains("arm.links[1].length: expected a number"));
}
