// The arrow primitive: its shaft and head end where the vector says, on generated vectors.
#include <catch2/catch.hpp>
#include <limits>
#include <random>

#include "render/arrow.hpp"

using namespace stiction::render;
using Catch::WithinAbs;

namespace {
glm::vec3 apply(const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1)); }
}  // namespace

TEST_CASE("an arrow runs from its tail to tail + vector on random vectors", "[arrow]") {
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 tail(u(rng), u(rng), u(rng));
    const glm::vec3 vector(u(rng), u(rng), u(rng));
    std::vector<DrawItem> items;
    add_arrow(items, tail, vector, Material{}, ArrowStyle{.shaft_radius = 0.01f});
    REQUIRE(items.size() == 2);
    REQUIRE(items[0].shape == Shape::cylinder);
    REQUIRE(items[1].shape == Shape::cone);
    const glm::vec3 shaft_start = apply(items[0].model, {0, 0, -1});
    const glm::vec3 apex = apply(items[1].model, {0, 0, 1});
    const glm::vec3 head_base = apply(items[1].model, {0, 0, 0});
    const glm::vec3 shaft_end = apply(items[0].model, {0, 0, 1});
    for (int k = 0; k < 3; ++k) {
      CHECK_THAT(shaft_start[k], WithinAbs(tail[k], 1e-5));
      CHECK_THAT(apex[k], WithinAbs(tail[k] + vector[k], 1e-5));
      CHECK_THAT(head_base[k], WithinAbs(shaft_end[k], 1e-5));
    }
    // The head is as wide as 2.2 shaft radii, across the arrow.
    const glm::vec3 rim = apply(items[1].model, {1, 0, 0}) - head_base;
    CHECK_THAT(glm::length(rim), WithinAbs(0.022, 1e-5));
    CHECK_THAT(glm::dot(rim, vector), WithinAbs(0.0, 1e-5));
  }
}

TEST_CASE("a zero or non-finite arrow adds nothing", "[arrow]") {
  std::vector<DrawItem> items;
  add_arrow(items, {0, 0, 0}, {0, 0, 0}, Material{});
  add_arrow(items, {0, 0, 0}, {std::numeric_limits<float>::quiet_NaN(), 0, 0}, Material{});
  CHECK(items.empty());
}
