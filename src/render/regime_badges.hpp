// "stick" / "slip" / "open" badges by each contact point and friction joint (of a planar
// arm or a kinematic tree: a URDF robot's <dynamics friction>), on the CPU
// overlay, coloured as the trail (green, red) and grey for open. The regime is judged with
// the element's own stick threshold, as the stick/slip events are. Points of one contact
// table in the same regime share one badge ("stick ×4", at their mean projected position),
// and badges that would overlap are pushed down below one another, so a box's corners never
// pile up; points that never touch during the run (a box's top corners) get none.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/contact_sites.hpp"
#include "render/overlay.hpp"
#include "render/scene_view.hpp"
#include "text/font.hpp"

namespace stiction::render {

enum class Regime { stick, slip, open };
const char* regime_name(Regime r);

// Open: the normal force column reads zero (no force); else stick while the slip speed is
// below the threshold (the rule of the events: core/slip_observer), slip otherwise. With an
// `exposure` (a frame's simulated duration) the regime over [t - exposure / 2, t +
// exposure / 2]: open only if open throughout, slip if it slipped while closed at any time,
// so a stiff contact's sub-millisecond hops do not make the badge flicker "open".
// `visible_gap` (metres, 0: off): a contact point closer to its surface than this counts as
// touching even where the rows show no force. A stiff contact that bounces at micrometres
// touches between the output rows (sphere_roll's ball hops about 60 um and touches for
// 0.5 ms between 1 kHz rows); the picture shows it resting on the ground, so the badge shows
// whether it slips rather than "open".
Regime contact_regime(const ContactSite& site, const PoseTrack& poses, double t,
                      double exposure = 0.0, double visible_gap = 0.0);
// The gap a viewer cannot see for a contact: a thousandth of its body's size.
double visible_gap(const Drawing& scene, const ContactSite& site);
// A friction joint: stick while |omega| of the joint is below its threshold.
Regime joint_regime(const JointSite& site, const PoseTrack& poses, double t);
// Where a friction joint is at time t (world): an arm's joint, or a tree link's joint (its
// frame's origin); nothing if the site names no joint of its body.
std::optional<core::Vec3> joint_position(const Drawing& scene, const JointSite& site,
                                         const PoseTrack& poses, double t);

// A badge to draw: its regime, how many points it stands for, and the projected points.
struct Badge {
  Regime regime = Regime::open;
  int count = 1;
  glm::vec2 anchor{0.0f};         // mean of the points, pixels (x right, y down)
  std::vector<glm::vec2> points;  // each point's projection
  std::string text() const;       // "slip" or "stick ×4"
  PixelBox box;                   // where it is drawn (after layout)
};

// Point `p` (world) in pixels of a width x height picture seen with `view_projection`;
// false if behind the camera.
bool project(const glm::mat4& view_projection, const glm::vec3& p, int width, int height,
             glm::vec2& pixel);

// Places each badge's box (`sizes`: text box width and height per badge) to the lower right
// of its anchor, moved down past each badge placed before it that it overlaps; if that
// covers boxes of `avoid` (the force arrows' pictures: a badge must not hide the friction
// arrow at its contact), the first of lower left, upper right and upper left of the anchor
// that overlaps no placed badge and covers fewer of their pixels, if there is one.
void lay_out_badges(std::vector<Badge>& badges, const std::vector<glm::vec2>& sizes,
                    const std::vector<PixelBox>& avoid = {});

class RegimeBadges {
 public:
  // Keeps the contact points that carry a normal force at some time of the run.
  RegimeBadges(const Drawing& scene, const ContactSites& sites, const PoseTrack& poses,
               int image_height);
  // The badges at time t (one per table and regime, one per joint), laid out.
  // `exposure`: the frame's simulated duration (contact_regime).
  // `avoid`: boxes the badges should not cover (lay_out_badges).
  std::vector<Badge> badges(const PoseTrack& poses, double t, const glm::mat4& view_projection,
                            int width, int height, double exposure = 0.0,
                            const std::vector<PixelBox>& avoid = {});
  void draw(image::Image& frame, const PoseTrack& poses, double t, const glm::mat4& view_projection,
            double exposure = 0.0, const std::vector<PixelBox>& avoid = {});

 private:
  Drawing scene_;
  ContactSites sites_;
  text::Font font_;
  text::TextStyle style_;
};

}  // namespace stiction::render
