// URDF bodies: the loader against frames composed here independently (generated chains with
// random origins, rpy, axes, inertials and fixed children), the two-link URDF scene against
// the planar two_link scene, the 6-DOF arm held and released by its joint friction, joint
// limits, and located errors.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>

#include "components/admittance/spatial_tree.hpp"
#include "scene/scene.hpp"
#include "scene/urdf_loader.hpp"

using namespace stiction;
using core::Mat3;
using core::Quat;
using core::Vec3;

namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("stiction_test_urdf_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
}

Quat rpy(const Vec3& a) {
  return Quat(Eigen::AngleAxisd(a.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(a.y(), Vec3::UnitY()) *
              Eigen::AngleAxisd(a.x(), Vec3::UnitX()));
}

std::string v3(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

// One rigid piece of a generated chain, in its moving link's frame chain.
struct Piece {
  double mass;
  Vec3 com_xyz, com_rpy;
  Mat3 inertia;  // in the inertial frame
};

struct GenLink {
  Vec3 origin, origin_rpy, axis;
  Piece piece;
  bool has_fixed = false;  // a fixed child under this link
  Vec3 fixed_xyz, fixed_rpy;
  Piece fixed_piece;
};

Piece random_piece(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Piece p;
  p.mass = 0.2 + 1.5 * (u(rng) + 1.0);
  p.com_xyz = 0.2 * Vec3(u(rng), u(rng), u(rng));
  p.com_rpy = 3.0 * Vec3(u(rng), u(rng), u(rng));
  // Principal moments satisfying the triangle inequality, turned by a random rotation.
  const Vec3 d(0.01 + 0.01 * (u(rng) + 1.0), 0.01 + 0.01 * (u(rng) + 1.0), 0.0);
  const Vec3 moments(d.x(), d.y(), d.x() + d.y() - 0.002);
  const Mat3 R = rpy(Vec3(u(rng), u(rng), u(rng))).toRotationMatrix();
  p.inertia = R * moments.asDiagonal() * R.transpose();
  return p;
}

std::string inertial(const Piece& p) {
  std::ostringstream s;
  s.precision(17);
  s << "<inertial><origin xyz=\"" << v3(p.com_xyz) << "\" rpy=\"" << v3(p.com_rpy)
    << "\"/><mass value=\"" << p.mass << "\"/><inertia ixx=\"" << p.inertia(0, 0) << "\" ixy=\""
    << p.inertia(0, 1) << "\" ixz=\"" << p.inertia(0, 2) << "\" iyy=\"" << p.inertia(1, 1)
    << "\" iyz=\"" << p.inertia(1, 2) << "\" izz=\"" << p.inertia(2, 2) << "\"/></inertial>";
  return s.str();
}

std::string chain_urdf(const std::vector<GenLink>& links) {
  std::ostringstream s;
  s << "<robot name=\"gen\"><link name=\"root\"/>";
  std::string parent = "root";
  for (std::size_t i = 0; i < links.size(); ++i) {
    const GenLink& l = links[i];
    const std::string name = std::string("l").append(std::to_string(i));
    s << "<joint name=\"j" << i << "\" type=\"continuous\"><parent link=\"" << parent
      << "\"/><child link=\"" << name << "\"/><origin xyz=\"" << v3(l.origin) << "\" rpy=\""
      << v3(l.origin_rpy) << "\"/><axis xyz=\"" << v3(l.axis) << "\"/></joint>";
    s << "<link name=\"" << name << "\">" << inertial(l.piece) << "</link>";
    if (l.has_fixed) {
      s << "<joint name=\"f" << i << "\" type=\"fixed\"><parent link=\"" << name
        << "\"/><child link=\"" << name << "_fixed\"/><origin xyz=\"" << v3(l.fixed_xyz)
        << "\" rpy=\"" << v3(l.fixed_rpy) << "\"/></joint>";
      s << "<link name=\"" << name << "_fixed\">" << inertial(l.fixed_piece) << "</link>";
    }
    parent = name;
  }
  s << "</robot>";
  return s.str();
}

// World mass, centre and inertia of every piece of joint i's subtree, composed here.
struct WorldPiece {
  int link;
  double mass;
  Vec3 com;
  Mat3 inertia;
};

void compose(const std::vector<GenLink>& links, const core::Vec& q, std::vector<Vec3>& joint_p,
             std::vector<Vec3>& joint_a, std::vector<WorldPiece>& pieces) {
  Vec3 p = Vec3::Zero();
  Quat r = Quat::Identity();
  auto add = [&](int link, const Vec3& fp, const Quat& fr, const Piece& piece) {
    const Vec3 c = fp + fr * piece.com_xyz;
    const Mat3 R = (fr * rpy(piece.com_rpy)).toRotationMatrix();
    pieces.push_back({link, piece.mass, c, R * piece.inertia * R.transpose()});
  };
  for (std::size_t i = 0; i < links.size(); ++i) {
    const GenLink& l = links[i];
    p = p + r * l.origin;
    r = r * rpy(l.origin_rpy);
    const Vec3 axis = l.axis.normalized();
    joint_p.push_back(p);
    joint_a.push_back(r * axis);
    r = r * Quat(Eigen::AngleAxisd(q[static_cast<Eigen::Index>(i)], axis));
    add(static_cast<int>(i), p, r, l.piece);
    if (l.has_fixed) add(static_cast<int>(i), p + r * l.fixed_xyz, r * rpy(l.fixed_rpy), l.fixed_piece);
  }
}

const components::SpatialTree& tree_of(const scene::Scene& s, const std::string& name) {
  for (const auto& a : s.network->admittances()) {
    if (a->name() == name) return dynamic_cast<const components::SpatialTree&>(*a);
  }
  throw std::runtime_error("no body " + name);
}

std::string source_dir() { return STICTION_SOURCE_DIR; }

}  // namespace

TEST_CASE("urdf loader: generated chains with fixed children match frames composed here",
          "[urdf]") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 2 + trial % 4;
    std::vector<GenLink> links(static_cast<std::size_t>(n));
    double total = 0.0;
    for (auto& l : links) {
      l.origin = 0.3 * Vec3(u(rng), u(rng), u(rng));
      l.origin_rpy = 3.0 * Vec3(u(rng), u(rng), u(rng));
      l.axis = Vec3(u(rng), u(rng), u(rng));
      l.piece = random_piece(rng);
      total += l.piece.mass;
      l.has_fixed = u(rng) > 0.0;
      if (l.has_fixed) {
        l.fixed_xyz = 0.3 * Vec3(u(rng), u(rng), u(rng));
        l.fixed_rpy = 3.0 * Vec3(u(rng), u(rng), u(rng));
        l.fixed_piece = random_piece(rng);
        total += l.fixed_piece.mass;
      }
    }
    const scene::UrdfRobot robot = scene::parse_urdf(chain_urdf(links), "gen.urdf");
    REQUIRE(robot.links.size() == links.size());
    double loaded = 0.0;
    for (const auto& l : robot.links) loaded += l.mass;
    CHECK(loaded == Approx(total).epsilon(1e-12));  // fixed children merged

    components::SpatialTreeParams params;
    params.links = robot.links;
    params.gravity = Vec3(0.0, 0.0, -9.8);
    const components::SpatialTree tree("gen", params);
    core::Vec q(n);
    for (int i = 0; i < n; ++i) q[i] = 3.0 * u(rng);
    std::vector<Vec3> jp, ja;
    std::vector<WorldPiece> pieces;
    compose(links, q, jp, ja, pieces);
    // Joint-space inertia H_ij = sum over pieces k below both joints of
    // a_i . I_k a_j + m_k (a_i x (c_k - p_i)) . (a_j x (c_k - p_j)).
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
    core::Vec gravity_torque = core::Vec::Zero(n);
    for (const WorldPiece& k : pieces) {
      for (int i = 0; i <= k.link; ++i) {
        const auto si = static_cast<std::size_t>(i);
        gravity_torque[i] += ja[si].dot((k.com - jp[si]).cross(k.mass * params.gravity));
        for (int j = 0; j <= k.link; ++j) {
          const auto sj = static_cast<std::size_t>(j);
          expected(i, j) += ja[si].dot(k.inertia * ja[sj]) +
                            k.mass * ja[si].cross(k.com - jp[si]).dot(ja[sj].cross(k.com - jp[sj]));
        }
      }
    }
    Eigen::MatrixXd H(n, n);
    tree.mass_matrix(q, H);
    CHECK((H - expected).norm() <= 1e-10 * (1.0 + expected.norm()));
    core::Vec c(n);
    tree.bias(q, core::Vec::Zero(n), c);
    // c holds minus gravity's generalized force.
    CHECK((c + gravity_torque).norm() <= 1e-10 * (1.0 + gravity_torque.norm()));
    const auto poses = tree.link_poses(q);
    for (int i = 0; i < n; ++i) CHECK((poses[static_cast<std::size_t>(i)].p - jp[static_cast<std::size_t>(i)]).norm() < 1e-12);
  }
}

TEST_CASE("urdf loader: a chain of 30000 joints loads without recursion, parents first",
          "[urdf]") {
  // Issue 39: the builder recursed once per joint and a long chain (a megabyte of XML)
  // overflowed the call stack (SIGSEGV in check and run). Every fifth link has a fixed child,
  // which the walk folds into its moving link.
  std::mt19937 rng(39);
  constexpr int kJoints = 30000;
  std::vector<GenLink> links(kJoints);
  for (std::size_t i = 0; i < links.size(); ++i) {
    GenLink& l = links[i];
    l.origin = Vec3(0.0, 0.0, 0.01);
    l.origin_rpy = Vec3::Zero();
    l.axis = Vec3::UnitY();
    l.piece = random_piece(rng);
    l.has_fixed = i % 5 == 0;
    l.fixed_xyz = Vec3(0.01, 0.0, 0.0);
    l.fixed_rpy = Vec3::Zero();
    l.fixed_piece = random_piece(rng);
  }
  const scene::UrdfRobot robot = scene::parse_urdf(chain_urdf(links), "long.urdf");
  REQUIRE(robot.links.size() == links.size());
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    REQUIRE(robot.links[i].parent == static_cast<int>(i) - 1);
    REQUIRE(robot.links[i].joint_name == std::string("j").append(std::to_string(i)));
  }
  // The fixed child's mass is folded into its link.
  CHECK(robot.links[0].mass == Approx(links[0].piece.mass + links[0].fixed_piece.mass));
  CHECK(robot.links[1].mass == Approx(links[1].piece.mass));
}

TEST_CASE("urdf scene: the two-link URDF arm follows two_link's trajectories", "[urdf]") {
  const std::vector<std::string> shorter{"simulation.duration=3.0"};
  scene::Scene planar = scene::load_scene(source_dir() + "/scenes/two_link.toml", shorter);
  scene::Scene urdf = scene::load_scene(source_dir() + "/scenes/two_link_urdf.toml", shorter);
  const core::RunResult a = core::simulate(*planar.network, planar.run);
  const core::RunResult b = core::simulate(*urdf.network, urdf.run);
  REQUIRE(a.trajectory.row_count() == b.trajectory.row_count());
  const std::vector<std::pair<std::string, std::string>> pairs{
      {"arm.theta.0", "arm.theta.shoulder"}, {"arm.theta.1", "arm.theta.elbow"},
      {"arm.omega.0", "arm.omega.shoulder"}, {"arm.omega.1", "arm.omega.elbow"}};
  double travel = 0.0;
  for (const auto& [pa, pb] : pairs) {
    const int ca = *a.trajectory.find(pa), cb = *b.trajectory.find(pb);
    double worst = 0.0;
    for (int r = 0; r < a.trajectory.row_count(); ++r) {
      worst = std::max(worst, std::abs(a.trajectory.at(r, ca) - b.trajectory.at(r, cb)));
      travel = std::max(travel, std::abs(a.trajectory.at(r, ca)));
    }
    INFO(pa << " vs " << pb);
    CHECK(worst < 1e-9);
  }
  CHECK(travel > 1.0);  // the arm did move
}

namespace {

// arm6.urdf with every joint friction scaled by `scale`, written to the temp dir.
fs::path scaled_arm6(double scale) {
  std::ifstream in(source_dir() + "/assets/robots/arm6.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str(), out;
  const std::string key = "friction=\"";
  std::size_t at = 0;
  while (true) {
    const std::size_t k = s.find(key, at);
    if (k == std::string::npos) break;
    const std::size_t start = k + key.size(), end = s.find('"', start);
    out += s.substr(at, start - at) + std::to_string(scale * std::stod(s.substr(start, end - start)));
    at = end;
  }
  out += s.substr(at);
  return write("arm6_scaled_" + std::to_string(scale) + ".urdf", out);
}

}  // namespace

TEST_CASE("urdf scene: arm6 holds below its friction level and settles inside the band above it",
          "[urdf]") {
  // Held: the bundled scene's pose, every gravity torque inside its joint's friction band.
  scene::Scene held = scene::load_scene(source_dir() + "/scenes/arm6_hold.toml",
                                        {"simulation.duration=3.0"});
  const auto& tree = tree_of(held, "arm");
  const int n = tree.joint_count();
  const core::Vec q0 = tree.params().angles;
  core::Vec c(n);
  tree.bias(q0, core::Vec::Zero(n), c);
  const scene::UrdfRobot robot = scene::load_urdf(source_dir() + "/assets/robots/arm6.urdf");
  for (int i = 0; i < n; ++i) REQUIRE(std::abs(c[i]) < robot.dynamics[static_cast<std::size_t>(i)].friction);
  const core::RunResult r = core::simulate(*held.network, held.run);
  const auto& tr = r.trajectory;
  // The elastic ringing of the stuck joints decays (by ~400 per second); over the last half
  // second no joint moves by 1e-9 rad.
  const int last = tr.row_count() - 1, mid = last * 5 / 6;
  const double K = 5000.0;  // the scene's friction_stiffness
  for (int i = 0; i < n; ++i) {
    const auto& link = tree.params().links[static_cast<std::size_t>(i)];
    const int col = *tr.find("arm.theta." + link.joint_name);
    INFO(link.joint_name);
    // The stuck joints' springs take the load in the first instants: no joint deflects by
    // more than its spring holds at the friction level (no slip); then nothing moves.
    double deflection = 0.0;
    for (int k = 0; k <= last; ++k) deflection = std::max(deflection, std::abs(tr.at(k, col) - q0[i]));
    CHECK(deflection <= robot.dynamics[static_cast<std::size_t>(i)].friction / K);
    // Zero drift: the friction's anchor q - e (the paper's invariant) does not move once
    // stuck; q itself still rings by ~1e-8 rad on the springs at the end.
    const int e = *tr.find("arm." + link.joint_name + ".friction.e");
    const double anchor_mid = tr.at(mid, col) - tr.at(mid, e);
    const double anchor_end = tr.at(last, col) - tr.at(last, e);
    const double anchor_0 = tr.at(0, col) - tr.at(0, e);
    CHECK(std::abs(anchor_end - anchor_mid) < 1e-9);
    CHECK(std::abs(anchor_end - anchor_0) < 1e-9);
    CHECK(std::abs(tr.at(last, col) - tr.at(mid, col)) < 1e-7);
  }

  // Released: friction cut to a fifth; it falls and stops where gravity is inside the band.
  const double scale = 0.2;
  const fs::path weak = scaled_arm6(scale);
  std::ifstream in(source_dir() + "/scenes/arm6_hold.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene_text = text.str();
  const std::string from = "../assets/robots/arm6.urdf";
  scene_text.replace(scene_text.find(from), from.size(), weak.string());
  scene::Scene fell = scene::load_scene(scene::SceneSource::from_text(scene_text, "arm6_weak.toml"),
                                        {"simulation.duration=6.0"});
  const core::RunResult f = core::simulate(*fell.network, fell.run);
  const auto& ft = f.trajectory;
  const int end = ft.row_count() - 1;
  const auto& weak_tree = tree_of(fell, "arm");
  core::Vec q(n);
  double moved = 0.0;
  for (int i = 0; i < n; ++i) {
    const std::string joint = weak_tree.params().links[static_cast<std::size_t>(i)].joint_name;
    q[i] = ft.at(end, *ft.find("arm.theta." + joint));
    moved = std::max(moved, std::abs(q[i] - q0[i]));
    CHECK(std::abs(ft.at(end, *ft.find("arm.omega." + joint))) < 1e-3);  // at rest
  }
  CHECK(moved > 0.05);  // it fell
  weak_tree.bias(q, core::Vec::Zero(n), c);
  for (int i = 0; i < n; ++i) {
    const auto& link = weak_tree.params().links[static_cast<std::size_t>(i)];
    if (q[i] >= link.upper - 1e-3 || q[i] <= link.lower + 1e-3) continue;  // held by a stop
    INFO(link.joint_name << ": q = " << q[i] << ", gravity torque " << c[i]);
    CHECK(std::abs(c[i]) <= scale * robot.dynamics[static_cast<std::size_t>(i)].friction + 1e-3);
  }
}

TEST_CASE("urdf scene: joint limits stop a falling pendulum at its upper limit", "[urdf]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.2, 0.9);
  for (int trial = 0; trial < 3; ++trial) {
    const double upper = u(rng), mass = 0.5 + u(rng), arm = 0.3 * u(rng);
    std::ostringstream urdf;
    urdf << "<robot name=\"p\"><link name=\"base\"/><joint name=\"hinge\" type=\"revolute\">"
         << "<parent link=\"base\"/><child link=\"bob\"/><axis xyz=\"0 1 0\"/>"
         << "<limit lower=\"-3\" upper=\"" << upper << "\" effort=\"1\" velocity=\"1\"/>"
         << "<dynamics damping=\"0.2\"/></joint><link name=\"bob\"><inertial><origin xyz=\""
         << arm << " 0 0\"/><mass value=\"" << mass
         << "\"/><inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/>"
         << "</inertial></link></robot>";
    const fs::path file = write("pendulum" + std::to_string(trial) + ".urdf", urdf.str());
    const std::string text = "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = 3.0\n"
                             "[bodies.p]\ntype = \"urdf\"\nfile = \"" + file.string() +
                             "\"\nlimit_stiffness = 2e4\nlimit_damping = 2.0\n";
    scene::Scene s = scene::load_scene(scene::SceneSource::from_text(text, "pendulum.toml"));
    const core::RunResult r = core::simulate(*s.network, s.run);
    const auto& t = r.trajectory;
    const int col = *t.find("p.theta.hinge");
    double peak = -1e9;
    for (int k = 0; k < t.row_count(); ++k) peak = std::max(peak, t.at(k, col));
    const double q_end = t.at(t.row_count() - 1, col);
    // At rest on the stop: K (q - upper) = m g arm cos(q).
    const double expected = upper + mass * 9.8 * arm * std::cos(upper) / 2e4;
    CHECK(q_end == Approx(expected).margin(1e-4));
    CHECK(peak < upper + 0.05);
  }
}

TEST_CASE("urdf scene: errors name the URDF file and the scene key", "[urdf]") {
  auto fails = [](const std::string& file, const std::string& what) {
    const std::string text = "[bodies.r]\ntype = \"urdf\"\nfile = \"" + file + "\"\n";
    try {
      scene::load_scene(scene::SceneSource::from_text(text, "robot.toml"));
      FAIL("loaded");
    } catch (const scene::InputError& e) {
      const std::string m = e.what();
      CHECK_THAT(m, Catch::Matchers::Contains("robot.toml:"));
      CHECK_THAT(m, Catch::Matchers::Contains("file"));
      CHECK_THAT(m, Catch::Matchers::Contains(file));
      CHECK_THAT(m, Catch::Matchers::Contains(what));
    }
  };
  fails((temp_dir() / "absent.urdf").string(), "cannot open");
  fails(write("bad.urdf", "<robot name=\"x\">\n<link name=\"a\">\n</robot>\n").string(), "bad.urdf:3:");
  fails(write("floating.urdf",
              "<robot name=\"x\"><link name=\"a\"/><link name=\"b\"/><joint name=\"free\" "
              "type=\"floating\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>")
            .string(),
        "floating");
  fails(write("none.urdf", "<robot name=\"x\"><link name=\"a\"/></robot>").string(), "no moving joint");
  // A joint name names columns: a comma would break trajectory.csv (issue 39).
  fails(write("comma.urdf",
              "<robot name=\"x\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j,1\" "
              "type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>")
            .string(),
        "joint 'j,1': component names may use letters, digits");
}

TEST_CASE("urdf loader: numbers are read strictly, at their line and attribute", "[urdf]") {
  // Issue 39: urdfdom read "1,5e-3" and "abc" as 0 and "nan" as NaN without a word, and a
  // mass of 1e308 came out as "massless links?".
  const auto robot = [](const std::string& inertial, const std::string& origin) {
    return "<robot name=\"x\">\n<link name=\"a\"/>\n<link name=\"b\">\n<inertial>" + inertial +
           "</inertial>\n</link>\n<joint name=\"j\" type=\"continuous\">\n<parent link=\"a\"/>"
           "<child link=\"b\"/><origin xyz=\"" + origin + "\"/><axis xyz=\"0 0 1\"/></joint>\n</robot>";
  };
  const std::string good_inertia =
      "<mass value=\"1\"/><inertia ixx=\"1e-3\" ixy=\"0\" ixz=\"0\" iyy=\"1e-3\" iyz=\"0\" izz=\"1e-3\"/>";
  REQUIRE(scene::parse_urdf(robot(good_inertia, "0 0 0.1"), "ok.urdf").links.size() == 1);
  const struct {
    std::string inertial, origin, where, why;
  } cases[] = {
      {"<mass value=\"1\"/><inertia ixx=\"1,5e-3\" ixy=\"0\" ixz=\"0\" iyy=\"1e-3\" iyz=\"0\" izz=\"1e-3\"/>",
       "0 0 0.1", "r.urdf:4:", "ixx=\"1,5e-3\": '1,5e-3' is not a number"},
      {"<mass value=\"abc\"/>", "0 0 0.1", "r.urdf:4:", "<mass> value=\"abc\""},
      {"<mass value=\"nan\"/>", "0 0 0.1", "r.urdf:4:", "is not finite"},
      {"<mass value=\"inf\"/>", "0 0 0.1", "r.urdf:4:", "is not finite"},
      {"<mass value=\"1e308\"/>", "0 0 0.1", "r.urdf:4:", "above 1e12"},
      {good_inertia, "0 0", "r.urdf:7:", "<origin> xyz=\"0 0\": has 2 number(s), 3 expected"},
      {good_inertia, "0 0 0.1x", "r.urdf:7:", "'0.1x' is not a number"},
  };
  for (const auto& c : cases) {
    INFO(c.why);
    try {
      scene::parse_urdf(robot(c.inertial, c.origin), "r.urdf");
      FAIL("parsed");
    } catch (const scene::UrdfError& e) {
      CHECK_THAT(e.what(), Catch::Matchers::Contains(c.where));
      CHECK_THAT(e.what(), Catch::Matchers::Contains(c.why));
    }
  }
}
