// Force and velocity arrows on generated scenes: a box of random size and orientation on a
// surface of random normal and a sphere on another, with random contact forces; the
// arrows must start at the contact points, split the force along the surface's normal and
// have the run's scale.
#include <catch2/catch.hpp>
#include <random>
#include <sstream>

#include "render/arrow_legend.hpp"
#include "render/contact_sites.hpp"
#include "render/force_arrows.hpp"
#include "render/regime_badges.hpp"
#include "render_fixtures.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

struct Generated {
  core::Vec3 box_size, box_p, floor_normal, ground_normal, sphere_p, sphere_v;
  core::Quat box_q;
  double radius = 0.1;
  std::vector<core::Vec3> forces;  // per box corner, then the sphere
  std::string toml;
};

core::Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return core::Vec3(n(rng), n(rng), n(rng)).normalized();
}

Generated generate(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Generated g;
  g.box_size = {0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng)};
  g.box_p = {u(rng), u(rng), u(rng)};
  g.box_q = core::Quat(Eigen::AngleAxisd(6.0 * u(rng), random_unit(rng)));
  g.floor_normal = random_unit(rng);
  g.ground_normal = random_unit(rng);
  g.radius = 0.05 + 0.5 * u(rng);
  g.sphere_p = {3.0 + u(rng), u(rng), u(rng)};
  g.sphere_v = 3.0 * random_unit(rng) * u(rng);
  for (int i = 0; i < 9; ++i) {
    // Some corners carry nothing (open), the others a force of random direction and size.
    g.forces.push_back(u(rng) < 0.3 ? core::Vec3::Zero()
                                    : core::Vec3(100.0 * u(rng) * random_unit(rng)));
  }
  std::ostringstream s;
  s.precision(17);
  auto v = [&](const core::Vec3& x) {
    std::ostringstream o;
    o.precision(17);
    o << "[" << x.x() << ", " << x.y() << ", " << x.z() << "]";
    return o.str();
  };
  s << "name = \"generated\"\ngravity = [0.0, 0.0, 0.0]\n"
    << "[bodies.box]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"box\"\nsize = " << v(g.box_size)
    << "\n[bodies.ball]\ntype = \"rigid_body\"\nmass = 1.0\nshape = \"sphere\"\nradius = "
    << g.radius << "\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\nnormal = "
    << v(g.floor_normal) << "\noffset = -5.0\n[impedances.ground]\ntype = \"kikuuwe_contact\"\n"
    << "body = \"ball\"\nnormal = " << v(g.ground_normal) << "\noffset = -5.0\n";
  g.toml = s.str();
  return g;
}

core::Trajectory trajectory_of(const Generated& g) {
  std::vector<std::string> columns{"t"};
  for (const char* b : {"box", "ball"}) {
    for (const char* a :
         {".p.x", ".p.y", ".p.z", ".q.w", ".q.x", ".q.y", ".q.z", ".v.x", ".v.y", ".v.z"}) {
      columns.push_back(std::string(b) + a);
    }
  }
  std::vector<std::string> contacts;
  for (int i = 0; i < 8; ++i) contacts.push_back("floor." + std::to_string(i));
  contacts.push_back("ground");
  for (const std::string& c : contacts) {
    for (const char* a : {".f.x", ".f.y", ".f.z"}) columns.push_back(c + a);
  }
  core::Trajectory tr(columns);
  for (double t : {0.0, 1.0}) {
    std::vector<double> row{t};
    auto pose = [&](const core::Vec3& p, const core::Quat& q, const core::Vec3& v) {
      row.insert(row.end(), {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z()});
    };
    pose(g.box_p, g.box_q, core::Vec3::Zero());
    pose(g.sphere_p, core::Quat::Identity(), g.sphere_v);
    for (const core::Vec3& f : g.forces) row.insert(row.end(), {f.x(), f.y(), f.z()});
    tr.append(row.data());
  }
  return tr;
}

glm::vec3 apply(const glm::mat4& m, const glm::vec3& p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

}  // namespace

TEST_CASE("contact sites: every corner of a generated box and a sphere's lowest point",
          "[render][forces]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 8; ++trial) {
    const Generated g = generate(rng);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const Drawing scene = s.drawing;
    const ContactSites sites = s.drawing.sites;
    REQUIRE(sites.contacts.size() == 9);
    const core::Trajectory tr = trajectory_of(g);
    const PoseTrack poses(tr, scene);
    // The corners, found independently of the order: each is one of p + q (+-h, +-h, +-h).
    std::vector<bool> seen(8, false);
    for (int i = 0; i < 8; ++i) {
      const ContactSite& c = sites.contacts[static_cast<std::size_t>(i)];
      CHECK(c.name == "floor." + std::to_string(i));
      CHECK(c.group == "floor");
      CHECK(c.radius == 0.0);
      const core::Vec3 local = g.box_q.conjugate() * (contact_point(c, poses, 0.5) - g.box_p);
      CHECK((local.cwiseAbs() - 0.5 * g.box_size).norm() < 1e-9);
      const int corner = (local.x() > 0) + 2 * (local.y() > 0) + 4 * (local.z() > 0);
      CHECK_FALSE(seen[static_cast<std::size_t>(corner)]);
      seen[static_cast<std::size_t>(corner)] = true;
    }
    const ContactSite& ball = sites.contacts.back();
    CHECK(ball.name == "ground");
    CHECK(ball.radius == Approx(g.radius));
    CHECK((contact_point(ball, poses, 0.5) - (g.sphere_p - g.radius * g.ground_normal)).norm() <
          1e-9);
  }
}

TEST_CASE("force arrows: normal along the surface normal, friction in the plane, at the scale",
          "[render][forces]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 8; ++trial) {
    const Generated g = generate(rng);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const Drawing scene = s.drawing;
    const ContactSites sites = s.drawing.sites;
    const core::Trajectory tr = trajectory_of(g);
    const PoseTrack poses(tr, scene);
    ArrowScales scales;
    scales.force = 50.0 + 100.0 * trial;
    scales.shaft_radius = 0.01f;
    const glm::vec3 eye{0.0f, -20.0f, 8.0f};
    std::vector<DrawItem> items;
    add_force_arrows(items, sites, poses, 0.5, scales, eye);
    std::size_t k = 0;
    for (std::size_t i = 0; i < sites.contacts.size(); ++i) {
      const ContactSite& c = sites.contacts[i];
      const core::Vec3 f = g.forces[i];
      if (f.isZero(0.0)) continue;
      const core::Vec3 n = i < 8 ? g.floor_normal : g.ground_normal;
      const core::Vec3 expected[2] = {n.dot(f) * n / scales.force,
                                      (f - n.dot(f) * n) / scales.force};
      const glm::vec3 tail = to_glm(force_arrow_tail(c, poses, 0.5, scales, eye));
      if (c.radius == 0.0) {
        // Off the corner by 1.5 shaft radii along the surface, out of the box: towards the
        // camera, or, where the box is on the camera's side of the corner (a back corner),
        // outwards from the box's centre.
        const core::Vec3 corner = contact_point(c, poses, 0.5);
        const glm::vec3 lifted = to_glm(corner + 0.01 * n);
        CHECK(glm::length(tail - lifted) == Approx(0.015f).margin(1e-5));
        CHECK(std::abs(glm::dot(tail - lifted, to_glm(n))) < 1e-5f);
        const core::Quat q = poses.orientation(c.body, 0.5);
        // Out of the box: out of one of the three faces that meet at the corner.
        auto leaves_box = [&](const core::Vec3& offset) {
          const core::Vec3 local = q.conjugate() * offset;
          return (c.local.array() * local.array() > 0.0).any();
        };
        CHECK(leaves_box(core::Vec3(tail.x, tail.y, tail.z) - corner));
        core::Vec3 toward = core::Vec3(eye.x, eye.y, eye.z) - corner;
        toward = (toward - n.dot(toward) * n).normalized();
        if (leaves_box(0.01 * n + 0.015 * toward)) {
          CHECK(glm::dot(eye - lifted, tail - lifted) > 0.0f);
        } else {
          core::Vec3 out = q * c.local;
          out = (out - n.dot(out) * n).normalized();
          CHECK(glm::dot(tail - lifted, to_glm(out)) == Approx(0.015f).margin(1e-5));
        }
      } else {
        // Beside the ball, not inside it, on the camera's side.
        const core::Vec3 d = core::Vec3(tail.x, tail.y, tail.z) - g.sphere_p;
        CHECK((d - n.dot(d) * n).norm() > g.radius);
        CHECK(glm::dot(eye - tail, tail - to_glm(contact_point(c, poses, 0.5))) > 0.0f);
      }
      for (const core::Vec3& e : expected) {
        REQUIRE(k + 1 < items.size());
        CHECK(items[k].shape == Shape::cylinder);
        CHECK(items[k + 1].shape == Shape::cone);
        CHECK_FALSE(items[k].casts_shadow);
        const glm::vec3 start = apply(items[k].model, {0.0f, 0.0f, -1.0f});
        const glm::vec3 tip = apply(items[k + 1].model, {0.0f, 0.0f, 1.0f});
        CHECK(glm::length(start - tail) < 1e-4f);
        CHECK(glm::length((tip - start) - to_glm(e)) < 1e-4f);
        k += 2;
      }
    }
    CHECK(k == items.size());
  }
}

TEST_CASE("force arrows: the automatic scale shows the largest force at 0.6 body sizes",
          "[render][forces]") {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 8; ++trial) {
    const Generated g = generate(rng);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const Drawing scene = s.drawing;
    const ContactSites sites = s.drawing.sites;
    const core::Trajectory tr = trajectory_of(g);
    const PoseTrack poses(tr, scene);
    OverlayLayers layers;
    layers.forces = layers.velocities = true;
    const ArrowScales scales = choose_arrow_scales(scene, sites, poses, layers);
    double largest = 0.0;
    for (std::size_t i = 0; i < sites.contacts.size(); ++i) {
      const ContactForce f = contact_force(sites.contacts[i], poses, 0.5);
      largest = std::max({largest, f.normal.norm(), f.friction.norm()});
    }
    const double size = std::max({g.box_size.maxCoeff(), 2.0 * g.radius});
    CHECK(arrow_body_size(scene) == Approx(size));
    CHECK(largest / scales.force == Approx(0.6 * size));
    CHECK(g.sphere_v.norm() / scales.velocity == Approx(0.8 * size));
    CHECK(scales.shaft_radius == Approx(0.025 * size));
    layers.force_scale = 7.0;
    CHECK(choose_arrow_scales(scene, sites, poses, layers).force == 7.0);
  }
  CHECK(round_up_125(0.7) == Approx(1.0));
  CHECK(round_up_125(1.0) == Approx(1.0));
  CHECK(round_up_125(13.0) == Approx(20.0));
  CHECK(round_up_125(210.0) == Approx(500.0));
}

TEST_CASE("velocity arrows start on the body's surface and have the velocity scale",
          "[render][forces]") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    const Generated g = generate(rng);
    const scene::Scene s = testing::make_scene(g.toml, "generated");
    const Drawing scene = s.drawing;
    const core::Trajectory tr = trajectory_of(g);
    const PoseTrack poses(tr, scene);
    ArrowScales scales;
    scales.velocity = 0.5 + trial;
    std::vector<DrawItem> items;
    add_velocity_arrows(items, scene, poses, 0.5, scales);
    REQUIRE(items.size() == 2);  // the box is at rest: only the ball's arrow
    const glm::vec3 start = apply(items[0].model, {0.0f, 0.0f, -1.0f});
    const glm::vec3 tip = apply(items[1].model, {0.0f, 0.0f, 1.0f});
    CHECK(glm::length(start - to_glm(g.sphere_p)) == Approx(g.radius).epsilon(1e-5));
    CHECK(glm::length((tip - start) - to_glm(g.sphere_v / scales.velocity)) < 1e-4f);
  }
}

TEST_CASE("arrow legend: a round value whose bar is 0.4 to 1 times the target length",
          "[render][forces]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> log10(-3.0, 3.0);
  for (int i = 0; i < 50; ++i) {
    const double scale = std::pow(10.0, log10(rng)), ppm = std::pow(10.0, 1.0 + log10(rng) / 2);
    const LegendBar bar = legend_bar(scale, ppm, 60.0);
    CHECK(bar.pixels <= 60.0 * (1.0 + 1e-9));
    CHECK(bar.pixels >= 0.4 * 60.0 * (1.0 - 1e-9));
    CHECK(bar.pixels == Approx(bar.value / scale * ppm));
    CHECK(round_up_125(bar.value) == Approx(bar.value));
  }
}

TEST_CASE("force arrows: impact spikes neither set the scale nor cross the picture",
          "[render][forces]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const Drawing scene = s.drawing;
  const ContactSites sites = s.drawing.sites;
  core::Trajectory tr({"t", "sphere.p.x", "sphere.p.y", "sphere.p.z", "sphere.q.w", "sphere.q.x",
                       "sphere.q.y", "sphere.q.z", "contact.f.x", "contact.f.y", "contact.f.z"});
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double steady = 1.0 + 5.0 * u(rng);
  for (int i = 0; i <= 2000; ++i) {
    const double t = 1e-3 * i;
    // A bounce: 100 times the steady force during 1 ms of every 40.
    const double f = i % 40 == 0 ? 100.0 * steady : steady;
    const double row[] = {t, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, f};
    tr.append(row);
  }
  const PoseTrack poses(tr, scene);
  OverlayLayers layers;
  layers.forces = true;
  const ArrowScales scales = choose_arrow_scales(scene, sites, poses, layers);
  CHECK(steady / scales.force == Approx(0.6 * 0.4));  // the body size: the 0.4 m diameter
  std::vector<DrawItem> items;
  add_force_arrows(items, sites, poses, 0.04, scales, {0.0f, -3.0f, 1.0f});  // a spike
  REQUIRE(items.size() == 2);
  const glm::vec3 start = apply(items[0].model, {0.0f, 0.0f, -1.0f});
  const glm::vec3 tip = apply(items[1].model, {0.0f, 0.0f, 1.0f});
  CHECK(glm::length(tip - start) == Approx(1.5 * 0.4).epsilon(1e-5));
}

TEST_CASE("force arrows: a bouncing contact shows its mean force over the frame's exposure",
          "[render][forces]") {
  const scene::Scene s = testing::make_scene(testing::sphere_roll_toml(), "sphere_roll");
  const Drawing scene = s.drawing;
  const ContactSites sites = s.drawing.sites;
  core::Trajectory tr({"t", "sphere.p.x", "sphere.p.y", "sphere.p.z", "sphere.q.w", "sphere.q.x",
                       "sphere.q.y", "sphere.q.z", "contact.f.x", "contact.f.y", "contact.f.z",
                       "contact.slip.x", "contact.slip.y", "contact.slip.z", "contact.n_force"});
  const double weight = 0.3 * 9.8;
  for (int i = 0; i <= 2000; ++i) {
    // Touching for one 1 kHz row in 20: an impulse of 20 x the weight (its mean is the weight).
    const double f = i % 20 == 0 ? 20.0 * weight : 0.0;
    const double row[] = {1e-3 * i, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 0.0,
                          0.1 * f,  0.0, f,   0.5, 0.0, 0.0, f};
    tr.append(row);
  }
  const PoseTrack poses(tr, scene);
  for (double t : {0.3, 0.3105, 0.317, 1.2}) {
    // Over an exposure of two bounces; instantaneously it is nothing or a spike.
    const ContactForce mean = contact_force(sites.contacts[0], poses, t, 0.04);
    CHECK(mean.normal.z() == Approx(weight).epsilon(0.15));
    CHECK(mean.friction.x() == Approx(0.1 * weight).epsilon(0.15));
    // Closed at some time of the exposure, slipping then: "slip", not "open".
    CHECK(contact_regime(sites.contacts[0], poses, t, 0.04) == Regime::slip);
  }
  CHECK(contact_force(sites.contacts[0], poses, 0.3105).normal.norm() == 0.0);
  CHECK(contact_regime(sites.contacts[0], poses, 0.3105) == Regime::open);
}
