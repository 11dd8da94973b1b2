#include "render/frame_panels.hpp"

#include <algorithm>

namespace stiction::render {

bool boxes_overlap(const PixelBox& a, const PixelBox& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

std::vector<PixelBox> free_rectangles(const FramePanels& panels) {
  const PixelBox frame{0, 0, panels.width, panels.height};
  std::vector<PixelBox> boxes;
  for (const PixelBox& b : panels.boxes) {
    const PixelBox cut{std::max(b.x0, 0), std::max(b.y0, 0), std::min(b.x1, panels.width),
                       std::min(b.y1, panels.height)};
    if (!cut.empty()) boxes.push_back(cut);
  }
  // A maximal free rectangle has each side on the frame's edge or on a panel's edge, so the
  // candidates are the rectangles between those coordinates (a few panels: a few hundred).
  std::vector<int> xs{0, panels.width}, ys{0, panels.height};
  for (const PixelBox& b : boxes) {
    xs.insert(xs.end(), {b.x0, b.x1});
    ys.insert(ys.end(), {b.y0, b.y1});
  }
  for (std::vector<int>* v : {&xs, &ys}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  auto is_free = [&](const PixelBox& r) {
    return std::none_of(boxes.begin(), boxes.end(),
                        [&](const PixelBox& b) { return boxes_overlap(r, b); });
  };
  std::vector<PixelBox> free;
  for (std::size_t a = 0; a < xs.size(); ++a) {
    for (std::size_t b = a + 1; b < xs.size(); ++b) {
      for (std::size_t c = 0; c < ys.size(); ++c) {
        for (std::size_t d = c + 1; d < ys.size(); ++d) {
          const PixelBox r{xs[a], ys[c], xs[b], ys[d]};
          if (is_free(r)) free.push_back(r);
        }
      }
    }
  }
  // Keep the maximal ones: those inside no other free rectangle.
  std::vector<PixelBox> maximal;
  for (const PixelBox& r : free) {
    const bool inside = std::any_of(free.begin(), free.end(), [&](const PixelBox& o) {
      return !(o == r) && o.x0 <= r.x0 && o.y0 <= r.y0 && o.x1 >= r.x1 && o.y1 >= r.y1;
    });
    if (!inside) maximal.push_back(r);
  }
  if (maximal.empty()) maximal.push_back(frame);  // panels cover it all: frame as if none
  return maximal;
}

}  // namespace stiction::render
