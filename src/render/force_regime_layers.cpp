#include "render/force_regime_layers.hpp"

#include <algorithm>

#include "render/title_caption.hpp"

namespace stiction::render {

std::unique_ptr<ForceRegimeLayers> ForceRegimeLayers::create(const Drawing& scene,
                                                             const ContactSites& sites,
                                                             const PoseTrack& poses,
                                                             const RenderSettings& settings) {
  const OverlayLayers& l = settings.overlay.layers;
  if (!settings.overlay.enabled || !(l.forces || l.velocities || l.badges)) return nullptr;
  return std::make_unique<ForceRegimeLayers>(scene, sites, poses, settings);
}

ForceRegimeLayers::ForceRegimeLayers(const Drawing& scene, const ContactSites& sites,
                                     const PoseTrack& poses, const RenderSettings& settings)
    : scene_(scene),
      sites_(sites),
      poses_(poses),
      layers_(settings.overlay.layers),
      aspect_(static_cast<float>(settings.width) / static_cast<float>(settings.height)) {
  if (layers_.forces || layers_.velocities) {
    scales_ = choose_arrow_scales(scene, sites_, poses, layers_,
                                  1.0 / (settings.fps * settings.slow_motion));
    legend_.emplace(layers_.forces, layers_.velocities, scales_, settings.height);
  }
  if (layers_.badges) badges_.emplace(scene, sites_, poses, settings.height);
  caption_height_ = TitleCaption::caption_height(settings.overlay, settings.height);
}

void ForceRegimeLayers::add_items(std::vector<DrawItem>& items, double t, const Camera& camera,
                                  double exposure) const {
  if (layers_.forces) add_force_arrows(items, sites_, poses_, t, scales_, camera.eye, exposure);
  if (layers_.velocities) add_velocity_arrows(items, scene_, poses_, t, scales_);
}

namespace {

// The legend's lowest row: above the caption's band, by the overlay's pad.
int legend_bottom(int height, int caption_height) {
  return height - caption_height - static_cast<int>(0.6 * std::max(11.0, height / 30.0));
}

}  // namespace

PixelBox ForceRegimeLayers::legend_box(int height) {
  return legend_ ? legend_->bound(legend_bottom(height, caption_height_)) : PixelBox{};
}

void ForceRegimeLayers::draw(image::Image& frame, double t, const Camera& camera, double exposure) {
  if (badges_) {
    badges_->draw(frame, poses_, t, camera.projection(aspect_) * camera.view(), exposure);
  }
  if (legend_) legend_->draw(frame, camera, legend_bottom(frame.height, caption_height_));
}

}  // namespace stiction::render
