// The part of the frame where a shadow can fall, as a rectangle of pixels. Sampling the
// shadow map is about a quarter of llvmpipe's work per frame, and most of the frame (the
// ground away from the bodies) can never be in shadow: the renderer draws with shadow
// sampling inside this rectangle only, and with a program that samples nothing outside it
// (where the map would have said "lit" anyway), so the picture is the same.
//
// A point reads a shadow only if it lies behind the nearest caster along the light and over
// the casters' footprint widened by the filter's reach: a prism along the light. For each
// item that prism is cut with the item's box (its unit shape's bounds under its model
// matrix, flat for a plane), and the pieces are projected to the screen. Conservative: the
// whole frame when a piece reaches behind the camera.
#pragma once

#include <vector>

#include "render/camera.hpp"
#include "render/scene_view.hpp"
#include "render/shadow_fit.hpp"

namespace stiction::render {

// Pixels [x0, x1) x [y0, y1) in GL window coordinates (origin at the bottom left).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  long area() const { return empty() ? 0 : long(x1 - x0) * long(y1 - y0); }
};

// Empty when the fit casts nothing.
PixelRect shadow_region(const std::vector<DrawItem>& items, const ShadowFit& fit,
                        const Camera& camera, int width, int height);

// The frame minus `inner`: up to four rectangles that do not overlap.
std::vector<PixelRect> complement(const PixelRect& inner, int width, int height);

}  // namespace stiction::render
