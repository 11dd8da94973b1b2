// Pixel helpers of the overlay tests: the pixels two renders of the same frame differ in (an
// overlay drawn over the same scene, one render with it and one without), and how far a
// point is from the nearest of them.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "image/image.hpp"

namespace stiction::render::testing {

// The centres of the pixels whose colour differs by more than 24 in some channel between two
// frames of the same size, leaving out those `skip(x, y)` names (a panel's pixels, say).
inline std::vector<glm::vec2> changed_pixels(const image::Image& a, const image::Image& b,
                                             const std::function<bool(int, int)>& skip = {}) {
  std::vector<glm::vec2> out;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (skip && skip(x, y)) continue;
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(a.width) +
                                 static_cast<std::size_t>(x));
      int d = 0;
      for (int c = 0; c < 3; ++c)
        d = std::max(d, std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])));
      if (d > 24) out.emplace_back(float(x) + 0.5f, float(y) + 0.5f);
    }
  }
  return out;
}

// The distance from p to the nearest of `pixels` (infinity when there are none).
inline float nearest(const std::vector<glm::vec2>& pixels, const glm::vec2& p) {
  float best = std::numeric_limits<float>::infinity();
  for (const glm::vec2& q : pixels) best = std::min(best, glm::length(q - p));
  return best;
}

}  // namespace stiction::render::testing
