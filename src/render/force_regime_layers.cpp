#include "render/force_regime_layers.hpp"

#include <algorithm>
#include <cmath>

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
    const glm::mat4 vp = camera.projection(aspect_) * camera.view();
    // The badges keep off the force arrows' pictures: a badge to the lower right of a wheel's
    // contact hid its friction arrow, which points forward along the floor.
    std::vector<PixelBox> arrows;
    if (layers_.forces) {
      const glm::vec3 right = glm::normalize(glm::cross(camera.target - camera.eye, camera.up));
      for (const ArrowSegment& a :
           force_arrow_segments(sites_, poses_, t, scales_, camera.eye, exposure)) {
        glm::vec2 tail, tip, side;
        const glm::vec3 from = to_glm(a.tail);
        if (!project(vp, from, frame.width, frame.height, tail) ||
            !project(vp, to_glm(a.tip), frame.width, frame.height, tip) ||
            !project(vp, from + 2.2f * scales_.shaft_radius * right, frame.width, frame.height,
                     side)) {
          continue;
        }
        const float pad = glm::length(side - tail) + 1.0f;  // the head's radius
        arrows.push_back({static_cast<int>(std::floor(std::min(tail.x, tip.x) - pad)),
                          static_cast<int>(std::floor(std::min(tail.y, tip.y) - pad)),
                          static_cast<int>(std::ceil(std::max(tail.x, tip.x) + pad)),
                          static_cast<int>(std::ceil(std::max(tail.y, tip.y) + pad))});
      }
    }
    badges_->draw(frame, poses_, t, vp, exposure, arrows);
  }
  if (legend_) legend_->draw(frame, camera, legend_bottom(frame.height, caption_height_));
}

}  // namespace stiction::render
