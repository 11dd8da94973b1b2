#include "render/shadow_region.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace stiction::render {
namespace {

using Polygon = std::vector<glm::vec3>;

// Points p with dot(n, p) + d >= 0.
struct HalfSpace {
  glm::vec3 n;
  float d;
  float at(const glm::vec3& p) const { return glm::dot(n, p) + d; }
};

// Sutherland-Hodgman: the part of a convex polygon inside a half-space.
Polygon clip(const Polygon& polygon, const HalfSpace& h) {
  Polygon out;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3& a = polygon[i];
    const glm::vec3& b = polygon[(i + 1) % n];
    const float da = h.at(a), db = h.at(b);
    if (da >= 0.0f) out.push_back(a);
    if ((da >= 0.0f) != (db >= 0.0f)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// Light-space coordinate `row` of a world point, as a plane: dot(n, p) + offset.
HalfSpace light_axis(const glm::mat4& light_view, int row, float sign, float bound) {
  const glm::vec3 n(light_view[0][row], light_view[1][row], light_view[2][row]);
  // sign * (dot(n, p) + t) >= sign * bound
  return {sign * n, sign * (light_view[3][row] - bound)};
}

}  // namespace

PixelRect shadow_region(const std::vector<DrawItem>& items, const ShadowFit& fit,
                        const Camera& camera, int width, int height) {
  PixelRect none;
  if (fit.empty) return none;
  const PixelRect whole{0, 0, width, height};

  // The prism: over the footprint widened by the filter's reach (the taps reach 0.75 of the
  // soft edge, the linear filter one texel, rasterization of the casters one more), behind
  // the nearest caster. The slack covers float rounding at the scene's scale.
  const glm::vec2 extent = fit.casters_max - fit.casters_min;
  const float slack = 1e-4f + 1e-3f * std::max(extent.x, extent.y);
  const float reach = 0.75f * fit.softness + 2.0f * fit.texel + slack;
  const glm::mat4& lv = fit.light_view;
  const std::array<HalfSpace, 5> prism = {
      light_axis(lv, 0, 1.0f, fit.casters_min.x - reach),
      light_axis(lv, 0, -1.0f, fit.casters_max.x + reach),
      light_axis(lv, 1, 1.0f, fit.casters_min.y - reach),
      light_axis(lv, 1, -1.0f, fit.casters_max.y + reach),
      light_axis(lv, 2, -1.0f, fit.casters_near + slack),
  };
  // The cap's corners (nearest the light): world points.
  const glm::mat4 to_world = glm::inverse(lv);
  std::array<glm::vec3, 4> cap;
  for (int i = 0; i < 4; ++i) {
    const glm::vec4 q((i & 1) ? fit.casters_max.x + reach : fit.casters_min.x - reach,
                      (i & 2) ? fit.casters_max.y + reach : fit.casters_min.y - reach,
                      fit.casters_near + slack, 1.0f);
    cap[static_cast<std::size_t>(i)] = glm::vec3(to_world * q);
  }

  const float aspect = float(width) / float(height);
  const glm::mat4 view_proj = camera.projection(aspect) * camera.view();
  glm::vec2 lo(1e30f), hi(-1e30f);
  bool any = false;
  // false: a point is behind the camera (its projection is unbounded).
  auto add = [&](const glm::vec3& p) {
    const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
    if (c.w <= 1e-6f) return false;
    const glm::vec2 ndc = glm::vec2(c) / c.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
    any = true;
    return true;
  };

  // The faces of the unit cube (a plane's is flat: z = 0), as corner indices.
  static constexpr int kFaces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const DrawItem& item : items) {
    const std::array<glm::vec3, 8> corner = shape_corners(item);
    Bounds box;
    for (const glm::vec3& p : corner) box.add(p);
    // The item's surface inside the prism: each face clipped by the prism's half-spaces.
    for (const auto& face : kFaces) {
      Polygon polygon;
      for (int k : face) polygon.push_back(corner[static_cast<std::size_t>(k)]);
      for (const HalfSpace& h : prism) {
        polygon = clip(polygon, h);
        if (polygon.empty()) break;
      }
      for (const glm::vec3& p : polygon) {
        if (!add(p)) return whole;
      }
    }
    // The prism's own corners inside the item (a caster sunk into a receiver): tested
    // against the item's axis-aligned bounds, which contain it (conservative).
    for (const glm::vec3& p : cap) {
      if (glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max))) {
        if (!add(p)) return whole;
      }
    }
  }
  if (!any) return none;
  // To pixels, widened by two for the samples of the pixels on the edge and for rounding.
  PixelRect r;
  r.x0 = std::max(0, static_cast<int>(std::floor((lo.x + 1.0f) * 0.5f * float(width))) - 2);
  r.y0 = std::max(0, static_cast<int>(std::floor((lo.y + 1.0f) * 0.5f * float(height))) - 2);
  r.x1 = std::min(width, static_cast<int>(std::ceil((hi.x + 1.0f) * 0.5f * float(width))) + 2);
  r.y1 = std::min(height, static_cast<int>(std::ceil((hi.y + 1.0f) * 0.5f * float(height))) + 2);
  if (r.empty()) return none;
  return r;
}

std::vector<PixelRect> complement(const PixelRect& inner, int width, int height) {
  if (inner.empty()) return {PixelRect{0, 0, width, height}};
  std::vector<PixelRect> out;
  const PixelRect parts[4] = {
      {0, 0, width, inner.y0},                  // below
      {0, inner.y1, width, height},             // above
      {0, inner.y0, inner.x0, inner.y1},        // left
      {inner.x1, inner.y0, width, inner.y1},    // right
  };
  for (const PixelRect& p : parts) {
    if (!p.empty()) out.push_back(p);
  }
  return out;
}

}  // namespace stiction::render
