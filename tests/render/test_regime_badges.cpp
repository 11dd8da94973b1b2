// Stick / slip / open badges: the regime against the element's own threshold (random slips
// on both sides of random thresholds), one badge per contact table and regime, and a layout
// in which no two badges overlap.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "render/camera.hpp"
#include "render/regime_badges.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

// A box of the given size resting on the floor (z = 0), turned about z by `yaw`; at t = 0
// its bottom corners all stick, at t = 1 they carry `normal` N each (0: open) and slip at
// `slip` m/s; the top corners never touch.
core::Trajectory box_trajectory(const core::Vec3& size, double yaw,
                                const std::vector<double>& normal,
                                const std::vector<double>& slip) {
  std::vector<std::string> columns{"t",       "box.p.x", "box.p.y", "box.p.z",
                                   "box.q.w", "box.q.x", "box.q.y", "box.q.z"};
  for (int i = 0; i < 8; ++i) {
    for (const char* a : {".n_force", ".slip.x", ".slip.y", ".slip.z"}) {
      columns.push_back("floor." + std::to_string(i) + a);
    }
  }
  core::Trajectory tr(columns);
  for (double t : {0.0, 1.0}) {
    std::vector<double> row{
        t, 0.0, 0.0, 0.5 * size.z(), std::cos(0.5 * yaw), 0.0, 0.0, std::sin(0.5 * yaw)};
    for (int i = 0; i < 8; ++i) {
      const bool bottom = (i & 4) == 0;
      const std::size_t k = static_cast<std::size_t>(i);
      row.insert(row.end(), {bottom ? (t == 0.0 ? 5.0 : normal[k]) : 0.0,
                             bottom && t == 1.0 ? slip[k] : 0.0, 0.0, 0.0});
    }
    tr.append(row.data());
  }
  return tr;
}

std::string box_toml(const core::Vec3& size) {
  return "name = \"box\"\n[bodies.box]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"box\"\n"
         "size = [" +
         std::to_string(size.x()) + ", " + std::to_string(size.y()) + ", " +
         std::to_string(size.z()) +
         "]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\nstick_threshold = "
         "0.01\n";
}

}  // namespace

TEST_CASE("badges: the regime against each element's own stick threshold", "[render][badges]") {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 40; ++i) {
    ContactSite site;
    site.name = "c";
    site.stick_threshold = std::pow(10.0, -5.0 + 4.0 * u(rng));
    const double slip = site.stick_threshold * (u(rng) < 0.5 ? u(rng) : 1.0 + 10.0 * u(rng));
    const double normal = u(rng) < 0.25 ? 0.0 : 10.0 * u(rng) + 1e-6;
    core::Trajectory tr({"t", "c.slip.x", "c.slip.y", "c.slip.z", "c.n_force"});
    for (double t : {0.0, 1.0}) {
      // Slip split over two axes: the norm is compared, as the events do.
      const double row[] = {t, slip * 0.6, slip * 0.8, 0.0, normal};
      tr.append(row);
    }
    const PoseTrack poses(tr, Drawing{});
    const Regime expected = normal == 0.0                 ? Regime::open
                            : slip < site.stick_threshold ? Regime::stick
                                                          : Regime::slip;
    CHECK(contact_regime(site, poses, 0.5) == expected);

    JointSite joint{"j", "arm", 0, 1, site.stick_threshold};
    core::Trajectory jt({"t", "arm.omega.0", "arm.omega.1"});
    for (double t : {0.0, 1.0}) {
      const double row[] = {t, 0.0, -slip};  // a negative rate slips as a positive one
      jt.append(row);
    }
    CHECK(joint_regime(joint, PoseTrack(jt, Drawing{}), 0.5) ==
          (slip < site.stick_threshold ? Regime::stick : Regime::slip));
  }
}

TEST_CASE("badges: a box's corners share one badge per regime, none for corners never touching",
          "[render][badges]") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    const core::Vec3 size{0.1 + u(rng), 0.1 + u(rng), 0.1 + u(rng)};
    const scene::Scene s = testing::make_scene(box_toml(size), "box");
    const Drawing scene = s.drawing;
    const ContactSites sites = s.drawing.sites;
    REQUIRE(sites.contacts.size() == 8);
    CHECK(sites.contacts[0].stick_threshold == 0.01);
    // Bottom corners: random regimes (open, stick below 0.01 m/s, slip above).
    std::vector<double> normal(8, 0.0), slip(8, 0.0);
    for (int i = 0; i < 4; ++i) {
      const double r = u(rng);
      normal[static_cast<std::size_t>(i)] = r < 0.33 ? 0.0 : 5.0;
      slip[static_cast<std::size_t>(i)] = r < 0.66 ? 0.002 : 0.5;
    }
    const core::Trajectory tr = box_trajectory(size, 6.0 * u(rng), normal, slip);
    const PoseTrack poses(tr, scene);
    RegimeBadges badges(scene, sites, poses, 360);
    Camera camera;
    camera.eye = {0.3f, -3.0f, 2.0f};
    camera.target = {0.0f, 0.0f, 0.2f};
    const glm::mat4 vp = camera.projection(640.0f / 360.0f) * camera.view();
    const std::vector<Badge> all = badges.badges(poses, 1.0, vp, 640, 360);
    int counts[3] = {0, 0, 0};
    int total = 0;
    for (const Badge& b : all) {
      CHECK(b.count == static_cast<int>(b.points.size()));
      counts[static_cast<int>(b.regime)] += b.count;
      total += b.count;
      CHECK(b.text() == (b.count == 1 ? std::string(regime_name(b.regime))
                                      : std::string(regime_name(b.regime)) + " \u00d7" +
                                            std::to_string(b.count)));
    }
    // The top corners never touch and have no badge. A bottom corner without force still
    // rests on the floor (no visible gap): its badge says whether it slips.
    int want[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i) ++want[slip[static_cast<std::size_t>(i)] < 0.01 ? 0 : 1];
    CHECK(total == 4);
    for (int r = 0; r < 3; ++r) CHECK(counts[r] == want[r]);
    CHECK(all.size() <= 3);
    for (std::size_t i = 0; i < all.size(); ++i) {
      for (std::size_t j = i + 1; j < all.size(); ++j) {
        const PixelBox &a = all[i].box, &b = all[j].box;
        CHECK_FALSE((a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1));
      }
    }
  }
}

TEST_CASE("badges: a contact without force is open only where its gap can be seen",
          "[render][badges]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 30; ++i) {
    const double radius = 0.02 + 0.5 * u(rng);
    const double threshold = 1e-3;
    const scene::Scene s = testing::make_scene(
        "name = \"ball\"\n[bodies.ball]\ntype = \"rigid_body\"\nmass = 1.0\nshape = "
        "\"sphere\"\nradius = " +
            std::to_string(radius) +
            "\n[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\n",
        "ball");
    const Drawing scene = s.drawing;
    const ContactSites sites = s.drawing.sites;
    REQUIRE(sites.contacts.size() == 1);
    const double gap_limit = visible_gap(scene, sites.contacts[0]);
    CHECK(gap_limit == Approx(2e-3 * radius));
    // Airborne by a random fraction of the visible gap or by many times it, no force in any
    // row, slipping or not.
    const bool hop = u(rng) < 0.5;
    const double height = hop ? gap_limit * 0.9 * u(rng) : gap_limit * (1.5 + 100.0 * u(rng));
    const double slip = u(rng) < 0.5 ? 0.1 * threshold : 10.0 * threshold;
    core::Trajectory tr({"t", "ball.p.x", "ball.p.y", "ball.p.z", "ball.q.w", "ball.q.x",
                         "ball.q.y", "ball.q.z", "ground.slip.x", "ground.slip.y", "ground.slip.z",
                         "ground.n_force"});
    for (double t : {0.0, 1.0}) {
      const double row[] = {t, 0.0, 0.0, radius + height, 1.0, 0.0, 0.0, 0.0, slip, 0.0, 0.0, 0.0};
      tr.append(row);
    }
    const PoseTrack poses(tr, scene);
    const Regime want = !hop ? Regime::open : slip < threshold ? Regime::stick : Regime::slip;
    CHECK(contact_regime(sites.contacts[0], poses, 0.5, 0.02, gap_limit) == want);
    // Without the rule, no force is open.
    CHECK(contact_regime(sites.contacts[0], poses, 0.5, 0.02) == Regime::open);
  }
}

TEST_CASE("badges: the layout leaves no two badges overlapping", "[render][badges]") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> x(0.0f, 200.0f), w(20.0f, 90.0f);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Badge> badges(1 + trial);
    std::vector<glm::vec2> sizes;
    for (Badge& b : badges) {
      b.anchor = {x(rng), 0.5f * x(rng)};  // crowded: many anchors on a small region
      sizes.emplace_back(w(rng), 18.0f);
    }
    lay_out_badges(badges, sizes);
    for (std::size_t i = 0; i < badges.size(); ++i) {
      const PixelBox& a = badges[i].box;
      CHECK(a.x1 - a.x0 == static_cast<int>(std::ceil(sizes[i].x)));
      CHECK(a.x0 == static_cast<int>(badges[i].anchor.x) + 8);  // beside its point
      CHECK(a.y0 >= static_cast<int>(badges[i].anchor.y));      // never above it
      for (std::size_t j = i + 1; j < badges.size(); ++j) {
        const PixelBox& b = badges[j].box;
        CHECK_FALSE((a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1));
      }
    }
  }
}

TEST_CASE("badges: the layout keeps off the force arrows where a side of the point is free",
          "[render][badges][forces]") {
  std::mt19937 rng(37);
  std::uniform_real_distribution<float> x(0.0f, 300.0f), w(20.0f, 90.0f), len(5.0f, 80.0f);
  auto overlaps = [](const PixelBox& a, const PixelBox& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
  };
  int moved_aside = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Badge> badges(1 + trial % 5);
    std::vector<glm::vec2> sizes;
    std::vector<PixelBox> arrows;
    for (Badge& b : badges) {
      b.anchor = {x(rng), 0.5f * x(rng)};
      sizes.emplace_back(w(rng), 18.0f);
      // An arrow from the point, horizontal or vertical (a friction or a normal force).
      const int ax = static_cast<int>(b.anchor.x), ay = static_cast<int>(b.anchor.y);
      const int l = static_cast<int>(len(rng));
      arrows.push_back(rng() % 2 == 0 ? PixelBox{ax - 3, ay - 3, ax + l, ay + 3}
                                      : PixelBox{ax - 3, ay - l, ax + 3, ay + 3});
    }
    lay_out_badges(badges, sizes, arrows);
    for (std::size_t i = 0; i < badges.size(); ++i) {
      const PixelBox& a = badges[i].box;
      const glm::vec2 p = badges[i].anchor;
      CHECK(a.x1 - a.x0 == static_cast<int>(std::ceil(sizes[i].x)));
      // Beside its point: one of the four sides, or below them, stacked.
      const bool right = a.x0 == static_cast<int>(p.x) + 8;
      const bool left = a.x1 == static_cast<int>(p.x) - 8;
      CHECK((right || left));
      for (std::size_t j = i + 1; j < badges.size(); ++j) CHECK_FALSE(overlaps(a, badges[j].box));
      const bool on_arrow = std::any_of(arrows.begin(), arrows.end(),
                                        [&](const PixelBox& r) { return overlaps(a, r); });
      if (!right || a.y0 < static_cast<int>(p.y)) ++moved_aside;
      if (on_arrow) {
        // Only when every other side of the point was taken by an arrow or a badge.
        const int ax = static_cast<int>(p.x), ay = static_cast<int>(p.y);
        const int bw = a.x1 - a.x0, bh = a.y1 - a.y0;
        for (const PixelBox& side : {PixelBox{ax - 8 - bw, ay + 4, ax - 8, ay + 4 + bh},
                                     PixelBox{ax + 8, ay - 4 - bh, ax + 8 + bw, ay - 4},
                                     PixelBox{ax - 8 - bw, ay - 4 - bh, ax - 8, ay - 4}}) {
          bool taken = std::any_of(arrows.begin(), arrows.end(),
                                   [&](const PixelBox& r) { return overlaps(side, r); });
          for (std::size_t j = 0; j < badges.size(); ++j) {
            if (j != i) taken |= overlaps(side, badges[j].box);
          }
          CHECK(taken);
        }
      }
    }
  }
  CHECK(moved_aside > 10);  // the arrows did move badges
}
