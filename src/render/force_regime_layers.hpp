// The forces-and-regimes layers of a video (issue 22), each off unless its [overlay] key
// turns it on: contact force arrows and velocity arrows (3-D items) with their legend, and
// stick/slip/open badges (CPU overlay). FrameRenderer holds one when any of them is on, so a
// run without them pays nothing.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "image/image.hpp"
#include "render/arrow_legend.hpp"
#include "render/camera.hpp"
#include "render/contact_sites.hpp"
#include "render/force_arrows.hpp"
#include "render/regime_badges.hpp"
#include "render/render_settings.hpp"

namespace stiction::render {

class ForceRegimeLayers {
 public:
  // Null when forces, velocities and badges are all off.
  static std::unique_ptr<ForceRegimeLayers> create(const Drawing& scene, const ContactSites& sites,
                                                   const PoseTrack& poses,
                                                   const RenderSettings& settings);
  ForceRegimeLayers(const Drawing& scene, const ContactSites& sites, const PoseTrack& poses,
                    const RenderSettings& settings);

  // The arrows at time t; `exposure`: the simulated time the frame stands for (forces and
  // regimes are judged over it: contact_force, contact_regime).
  void add_items(std::vector<DrawItem>& items, double t, const Camera& camera,
                 double exposure) const;
  // Badges and legend over the read-back frame.
  void draw(image::Image& frame, double t, const Camera& camera, double exposure);

  const ArrowScales& scales() const { return scales_; }
  // The most of a frame `height` high the arrows' legend can cover (ArrowLegend::bound);
  // empty without arrows.
  PixelBox legend_box(int height);

 private:
  const Drawing& scene_;
  ContactSites sites_;
  const PoseTrack& poses_;
  OverlayLayers layers_;
  float aspect_;
  int caption_height_ = 0;  // pixels the caption band takes at the bottom
  ArrowScales scales_;
  std::optional<ArrowLegend> legend_;
  std::optional<RegimeBadges> badges_;
};

}  // namespace stiction::render
