// The flat panels drawn over a frame (the time and value panel, the title and caption bands,
// the inset plot) and the part of the frame they leave free, where the automatic camera puts
// the bodies (framing.hpp): a body is never hidden under a panel.
#pragma once

#include <vector>

namespace stiction::render {

struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1), y down from the top row
  bool operator==(const PixelBox&) const = default;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

// True if the two boxes share a pixel.
bool boxes_overlap(const PixelBox& a, const PixelBox& b);

// A frame's size and the boxes its panels cover (empty boxes are ignored).
struct FramePanels {
  int width = 1280;
  int height = 720;
  std::vector<PixelBox> boxes;
  float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
};

// The maximal rectangles of the frame that no panel covers: each touches a panel or the
// frame's edge on all four sides, so none lies inside another. With no panels, the whole
// frame. With panels at the corners and edges (as they are drawn) there are a handful; the
// camera frames into each and keeps the one that shows the bodies largest.
std::vector<PixelBox> free_rectangles(const FramePanels& panels);

}  // namespace stiction::render
