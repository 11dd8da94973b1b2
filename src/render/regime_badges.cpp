#include "render/regime_badges.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>

#include "render/trail.hpp"
#include "render/tree_items.hpp"

namespace stiction::render {
namespace {

image::Rgba regime_colour(Regime r) {
  switch (r) {
    case Regime::stick:
      return {24, 140, 60, 255};  // the trail's green
    case Regime::slip:
      return {205, 30, 30, 255};  // the trail's red
    case Regime::open:
      return {115, 118, 124, 255};
  }
  return {0, 0, 0, 255};
}

bool overlaps(const PixelBox& a, const PixelBox& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

void fill(image::Image& frame, const PixelBox& box, image::Rgba colour, float coverage) {
  for (int y = std::max(0, box.y0); y < std::min(box.y1, frame.height); ++y) {
    for (int x = std::max(0, box.x0); x < std::min(box.x1, frame.width); ++x) {
      frame.blend(x, y, colour, coverage);
    }
  }
}

void dot(image::Image& frame, const glm::vec2& c, float radius, image::Rgba colour) {
  const int r = static_cast<int>(std::ceil(radius + 1.0f));
  for (int y = static_cast<int>(c.y) - r; y <= static_cast<int>(c.y) + r; ++y) {
    for (int x = static_cast<int>(c.x) - r; x <= static_cast<int>(c.x) + r; ++x) {
      if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) continue;
      const float d = std::hypot(x + 0.5f - c.x, y + 0.5f - c.y);
      // A white ring around the coloured disc so the dot reads on any background.
      if (d < radius)
        frame.blend(x, y, colour, std::clamp(radius - d, 0.0f, 1.0f));
      else if (d < radius + 1.5f)
        frame.blend(x, y, {255, 255, 255, 255}, 0.9f);
    }
  }
}

}  // namespace

std::optional<core::Vec3> joint_position(const Drawing& scene, const JointSite& site,
                                         const PoseTrack& poses, double t) {
  if (site.body < 0 || site.body >= static_cast<int>(scene.bodies.size()) || site.joint < 0) {
    return std::nullopt;
  }
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(site.body)];
  const auto j = static_cast<std::size_t>(site.joint);
  if (b.kind == BodyVisual::Kind::tree && b.tree != nullptr) {
    // A link's frame is its joint's frame after the joint's motion: its origin is the joint.
    const std::vector<components::LinkPose> links = tree_poses(b, poses, site.body, t);
    if (j < links.size()) return links[j].p;
  } else if (b.kind == BodyVisual::Kind::arm) {
    const std::vector<core::Vec3> joints = arm_joints(b, poses, site.body, t);
    if (j < joints.size()) return joints[j];
  }
  return std::nullopt;
}

const char* regime_name(Regime r) {
  switch (r) {
    case Regime::stick:
      return "stick";
    case Regime::slip:
      return "slip";
    case Regime::open:
      return "open";
  }
  return "";
}

double visible_gap(const Drawing& scene, const ContactSite& site) {
  if (site.body < 0 || site.body >= static_cast<int>(scene.bodies.size())) return 0.0;
  const BodyVisual& b = scene.bodies[static_cast<std::size_t>(site.body)];
  const double size = b.kind == BodyVisual::Kind::sphere ? 2.0 * b.radius : b.size.maxCoeff();
  return 1e-3 * size;
}

Regime contact_regime(const ContactSite& site, const PoseTrack& poses, double t, double exposure,
                      double visible_gap) {
  const int samples = exposure > 0.0 ? std::clamp(static_cast<int>(exposure / 5e-4), 4, 64) : 1;
  bool closed = false, slipped = false;
  for (int i = 0; i < samples; ++i) {
    const double s = samples == 1 ? t : t + exposure * ((i + 0.5) / samples - 0.5);
    const double normal_force = poses.signal(site.name + ".n_force", s);
    const bool pressed = std::isnan(normal_force) || normal_force > 0.0;
    if (!pressed) {
      if (!(visible_gap > 0.0)) continue;
      const SurfacePlane plane = surface_plane(site, poses, s);
      const double gap = plane.normal.dot(contact_point(site, poses, s) - plane.origin);
      if (!(gap < visible_gap)) continue;
    }
    closed = true;
    const double slip = poses.signal(site.name + ".slip", s);
    if (!(std::isnan(slip) || sticks(slip, site.stick_threshold))) slipped = true;
  }
  return !closed ? Regime::open : slipped ? Regime::slip : Regime::stick;
}

Regime joint_regime(const JointSite& site, const PoseTrack& poses, double t) {
  const double omega = poses.signal(rate_column(site), t);
  return std::isnan(omega) || sticks(std::abs(omega), site.stick_threshold) ? Regime::stick
                                                                            : Regime::slip;
}

std::string Badge::text() const {
  std::string s = regime_name(regime);
  if (count > 1) s += " \u00d7" + std::to_string(count);
  return s;
}

bool project(const glm::mat4& view_projection, const glm::vec3& p, int width, int height,
             glm::vec2& pixel) {
  const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
  if (clip.w <= 1e-6f) return false;
  const glm::vec2 ndc{clip.x / clip.w, clip.y / clip.w};
  pixel = {(0.5f * ndc.x + 0.5f) * static_cast<float>(width),
           (0.5f - 0.5f * ndc.y) * static_cast<float>(height)};
  return true;
}

void lay_out_badges(std::vector<Badge>& badges, const std::vector<glm::vec2>& sizes,
                    const std::vector<PixelBox>& avoid) {
  // Top to bottom, so pushing down never moves a badge onto one already settled above.
  std::vector<std::size_t> order(badges.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return badges[a].anchor.y < badges[b].anchor.y;
  });
  std::vector<PixelBox> placed;
  for (std::size_t i : order) {
    Badge& b = badges[i];
    const int w = static_cast<int>(std::ceil(sizes[i].x)),
              h = static_cast<int>(std::ceil(sizes[i].y));
    const int ax = static_cast<int>(b.anchor.x), ay = static_cast<int>(b.anchor.y);
    // Pixels of `c` under the arrows' boxes (counted once per box).
    auto on_arrows = [&](const PixelBox& c) {
      long area = 0;
      for (const PixelBox& a : avoid) {
        const long across = std::min(c.x1, a.x1) - std::max(c.x0, a.x0);
        const long down = std::min(c.y1, a.y1) - std::max(c.y0, a.y0);
        if (across > 0 && down > 0) area += across * down;
      }
      return area;
    };
    auto clear_of_badges = [&](const PixelBox& c) {
      return std::none_of(placed.begin(), placed.end(),
                          [&](const PixelBox& p) { return overlaps(c, p); });
    };
    // Lower right, lower left, upper right, upper left of the anchor.
    const PixelBox sides[] = {{ax + 8, ay + 4, ax + 8 + w, ay + 4 + h},
                              {ax - 8 - w, ay + 4, ax - 8, ay + 4 + h},
                              {ax + 8, ay - 4 - h, ax + 8 + w, ay - 4},
                              {ax - 8 - w, ay - 4 - h, ax - 8, ay - 4}};
    // To the lower right, moved down past the badges placed before it (badges of one place
    // read as a list below it) ...
    PixelBox box = sides[0];
    for (bool moved = true; moved;) {
      moved = false;
      for (const PixelBox& p : placed) {
        if (overlaps(box, p)) {
          box.y0 = p.y1 + 2;
          box.y1 = box.y0 + h;
          moved = true;
        }
      }
    }
    // ... unless that covers an arrow: then the side, clear of the badges, that covers the
    // arrows least (a normal force's arrow stands beside a friction's, so all four sides may
    // touch one).
    long covered = on_arrows(box);
    for (auto side = std::begin(sides) + 1; side != std::end(sides) && covered > 0; ++side) {
      const long c = on_arrows(*side);
      if (c < covered && clear_of_badges(*side)) {
        box = *side;
        covered = c;
      }
    }
    b.box = box;
    placed.push_back(box);
  }
}

RegimeBadges::RegimeBadges(const Drawing& scene, const ContactSites& sites, const PoseTrack& poses,
                           int image_height)
    : scene_(scene), font_(text::Font::open_default()) {
  style_.pixel_size = std::max(10.0, image_height / 40.0);
  style_.colour = {255, 255, 255, 255};
  sites_.joints = sites.joints;
  constexpr int kSamples = 128;
  const double t0 = poses.start_time(), t1 = poses.end_time();
  for (const ContactSite& s : sites.contacts) {
    for (int i = 0; i <= kSamples; ++i) {
      // Each sample stands for its stretch of the run (a short landing between samples
      // counts), with the frames' rule for a gap nobody can see.
      if (contact_regime(s, poses, t0 + (t1 - t0) * i / kSamples, (t1 - t0) / kSamples,
                         visible_gap(scene, s)) != Regime::open) {
        sites_.contacts.push_back(s);
        break;
      }
    }
  }
}

std::vector<Badge> RegimeBadges::badges(const PoseTrack& poses, double t,
                                        const glm::mat4& view_projection, int width, int height,
                                        double exposure, const std::vector<PixelBox>& avoid) {
  std::map<std::pair<std::string, Regime>, Badge> groups;  // ordered: the same every frame
  for (const ContactSite& s : sites_.contacts) {
    glm::vec2 pixel;
    if (!project(view_projection, to_glm(contact_point(s, poses, t)), width, height, pixel)) {
      continue;
    }
    const Regime r = contact_regime(s, poses, t, exposure, visible_gap(scene_, s));
    Badge& b = groups[{s.group, r}];
    b.regime = r;
    b.points.push_back(pixel);
  }
  for (const JointSite& j : sites_.joints) {
    const std::optional<core::Vec3> at = joint_position(scene_, j, poses, t);
    glm::vec2 pixel;
    if (!at || !project(view_projection, to_glm(*at), width, height, pixel)) continue;
    const Regime r = joint_regime(j, poses, t);
    Badge& b = groups[{j.name, r}];
    b.regime = r;
    b.points.push_back(pixel);
  }
  std::vector<Badge> out;
  std::vector<glm::vec2> sizes;
  for (auto& [key, b] : groups) {
    b.count = static_cast<int>(b.points.size());
    glm::vec2 sum{0.0f};
    for (const glm::vec2& p : b.points) sum += p;
    b.anchor = sum / static_cast<float>(b.count);
    const text::Extent e = font_.measure(b.text(), style_);
    const double pad = 0.35 * style_.pixel_size;
    sizes.emplace_back(e.width + 2.0 * pad, 1.3 * style_.pixel_size + pad);
    out.push_back(b);
  }
  lay_out_badges(out, sizes, avoid);
  return out;
}

void RegimeBadges::draw(image::Image& frame, const PoseTrack& poses, double t,
                        const glm::mat4& view_projection, double exposure,
                        const std::vector<PixelBox>& avoid) {
  const std::vector<Badge> all =
      badges(poses, t, view_projection, frame.width, frame.height, exposure, avoid);
  const float radius = static_cast<float>(0.22 * style_.pixel_size);
  for (const Badge& b : all) {
    for (const glm::vec2& p : b.points) dot(frame, p, radius, regime_colour(b.regime));
  }
  for (const Badge& b : all) {
    fill(frame, b.box, regime_colour(b.regime), 0.88f);
    const double pad = 0.35 * style_.pixel_size;
    font_.draw(frame, b.text(), b.box.x0 + pad, b.box.y0 + 0.5 * pad + 1.0 * style_.pixel_size,
               style_);
  }
}

}  // namespace stiction::render
