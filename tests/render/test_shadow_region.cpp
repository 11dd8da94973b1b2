// Shadow sampling only inside the region where a shadow can fall gives the same picture as
// sampling everywhere, on generated scenes: spheres, turned boxes and cylinders over ground
// tiles at any slope, a wall, cameras from any side.
#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "image/compare.hpp"
#include "image/png.hpp"
#include "render/gl_context.hpp"
#include "render/renderer.hpp"
#include "render/shadow_region.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

glm::mat4 turned(std::mt19937& rng) {
  std::uniform_real_distribution<float> angle(-3.14159f, 3.14159f), unit(-1.0f, 1.0f);
  glm::vec3 axis(unit(rng), unit(rng), unit(rng));
  if (glm::length(axis) < 1e-3f) axis = glm::vec3(0, 0, 1);
  return glm::rotate(glm::mat4(1.0f), angle(rng), glm::normalize(axis));
}

struct GeneratedScene {
  std::vector<DrawItem> items;
  Camera camera;
};

// Ground tiles (checker) on a plane tilted up to 35 degrees, an upright wall behind, and
// 1..6 bodies of random shape, size and attitude resting on or hovering over the ground.
GeneratedScene generate(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  GeneratedScene g;
  const glm::mat4 slope = glm::rotate(glm::mat4(1.0f), 0.6f * (u(rng) - 0.5f) * 2.0f,
                                      glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, 0.0f) +
                                                     glm::vec3(1e-3f, 0.0f, 0.0f)));
  for (int i = -2; i < 2; ++i) {
    for (int j = -2; j < 2; ++j) {
      DrawItem tile;
      tile.shape = Shape::plane;
      tile.casts_shadow = false;
      tile.model = slope * glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * i + 1.0f, 2.0f * j + 1.0f, 0.0f));
      tile.material.kind = MaterialKind::checker;
      tile.material.colour = glm::vec3(0.8f);
      tile.material.colour2 = glm::vec3(0.5f);
      tile.material.specular = 0.05f;
      g.items.push_back(tile);
    }
  }
  DrawItem wall;
  wall.shape = Shape::plane;
  wall.casts_shadow = false;
  wall.model = slope * glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.5f, 1.0f)) *
               glm::rotate(glm::mat4(1.0f), 1.5708f, glm::vec3(1, 0, 0)) *
               glm::scale(glm::mat4(1.0f), glm::vec3(3.0f, 1.0f, 1.0f));
  wall.material.colour = glm::vec3(0.6f, 0.65f, 0.7f);
  g.items.push_back(wall);

  const int bodies = 1 + static_cast<int>(u(rng) * 6.0f);
  for (int b = 0; b < bodies; ++b) {
    DrawItem body;
    const float pick = u(rng);
    body.shape = pick < 0.4f ? Shape::sphere : pick < 0.75f ? Shape::box : Shape::cylinder;
    const float size = 0.1f + 0.4f * u(rng);
    const glm::vec3 at(3.0f * (u(rng) - 0.5f), 3.0f * (u(rng) - 0.5f), size * (1.0f + 2.0f * u(rng)));
    const glm::vec3 scale = body.shape == Shape::sphere
                                ? glm::vec3(size)
                                : glm::vec3(size, size * (0.3f + u(rng)), size * (0.3f + u(rng)));
    body.model = slope * glm::translate(glm::mat4(1.0f), at) * turned(rng) *
                 glm::scale(glm::mat4(1.0f), scale);
    body.material.kind = body.shape == Shape::sphere ? MaterialKind::sphere_pattern : MaterialKind::plain;
    body.material.colour = glm::vec3(0.9f, 0.4f, 0.1f);
    body.material.colour2 = glm::vec3(0.9f);
    g.items.push_back(body);
  }
  // A camera from any side, above the ground, looking at the middle of the bodies.
  const float azimuth = 6.2832f * u(rng), elevation = 0.15f + 1.2f * u(rng);
  const float distance = 3.0f + 4.0f * u(rng);
  g.camera.target = glm::vec3(slope * glm::vec4(0.0f, 0.0f, 0.2f, 1.0f));
  g.camera.eye = g.camera.target + distance * glm::vec3(std::cos(azimuth) * std::cos(elevation),
                                                        std::sin(azimuth) * std::cos(elevation),
                                                        std::sin(elevation));
  return g;
}

}  // namespace

TEST_CASE("shadow region: its complement tiles the rest of the frame", "[render][shadow]") {
  const PixelRect inner{100, 50, 300, 200};
  long area = inner.area();
  for (const PixelRect& r : complement(inner, 640, 360)) {
    area += r.area();
    CHECK(r.x0 >= 0);
    CHECK(r.y0 >= 0);
    CHECK(r.x1 <= 640);
    CHECK(r.y1 <= 360);
    const bool overlaps = r.x0 < inner.x1 && inner.x0 < r.x1 && r.y0 < inner.y1 && inner.y0 < r.y1;
    CHECK_FALSE(overlaps);
  }
  CHECK(area == 640L * 360L);
  CHECK(complement(PixelRect{}, 640, 360).size() == 1);
  CHECK(complement(PixelRect{0, 0, 640, 360}, 640, 360).empty());
}

TEST_CASE("shadow region: the same picture as sampling the map everywhere, on generated scenes",
          "[render][shadow]") {
  auto context = create_offscreen_context();
  RendererOptions region_options;
  region_options.width = 480;
  region_options.height = 270;
  RendererOptions everywhere_options = region_options;
  everywhere_options.shadows_everywhere = true;
  RendererOptions unshadowed_options = region_options;
  unshadowed_options.shadow_map_size = 0;
  Renderer with_region(region_options), everywhere(everywhere_options),
      unshadowed(unshadowed_options);
  std::mt19937 rng(20261201);
  double region_share = 0.0;
  int shadowed_scenes = 0;
  const int scenes = 24;
  for (int i = 0; i < scenes; ++i) {
    const GeneratedScene g = generate(rng);
    with_region.draw(g.items, g.camera);
    const image::Image a = with_region.read_back();
    everywhere.draw(g.items, g.camera);
    const image::Image b = everywhere.read_back();
    unshadowed.draw(g.items, g.camera);
    const image::Image c = unshadowed.read_back();
    image::CompareOptions exact;
    exact.channel_tolerance = 1;
    exact.max_fraction = 0.0;
    const image::CompareResult r = image::compare_images(b, a, exact);
    INFO("scene " << i << ": " << r.message);
    if (!r.matches) {
      image::write_png(std::string(STICTION_TEST_OUTPUT_DIR) + "/failures/region_" +
                           std::to_string(i) + ".png", a);
      image::write_png(std::string(STICTION_TEST_OUTPUT_DIR) + "/failures/everywhere_" +
                           std::to_string(i) + ".png", b);
    }
    CHECK(r.matches);
    // The scenes do have shadows (else the comparison says nothing).
    if (image::compare_images(b, c, exact).fraction_off > 0.002) ++shadowed_scenes;
    const ShadowFit fit = fit_shadow(g.items, g.camera, 480.0f / 270.0f,
                                     light_direction(), 2048);
    region_share += double(shadow_region(g.items, fit, g.camera, 480, 270).area()) / (480.0 * 270.0);
  }
  CHECK(shadowed_scenes >= scenes * 3 / 4);
  // And the region is a part of the frame, not all of it.
  INFO("mean share of the frame in the region: " << region_share / scenes);
  CHECK(region_share / scenes < 0.6);
}
