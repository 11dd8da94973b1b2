// SpatialTree::derivative() allocates nothing: its scratch is sized once in the constructor
// (a step of a long run must not touch the heap). Counted by interposing malloc in this test
// executable (glibc: operator new and Eigen's dynamic matrices both end in malloc).
#include <atomic>
#include <catch2/catch.hpp>
#include <cstddef>

#include "components/admittance/spatial_tree.hpp"

namespace {
std::atomic<long> allocations{0};
}

extern "C" void* __libc_malloc(std::size_t size) noexcept;
extern "C" void* malloc(std::size_t size) noexcept {
  ++allocations;
  return __libc_malloc(size);
}

using namespace stiction;

TEST_CASE("spatial tree: derivative() does not allocate") {
  components::SpatialTreeParams p;
  for (int i = 0; i < 12; ++i) {
    components::SpatialLink l;
    l.joint_name = std::string("j").append(std::to_string(i));
    l.parent = i == 0 ? -1 : (i - 1) / 2;
    l.type = i % 3 == 2 ? components::SpatialJointType::prismatic
                        : components::SpatialJointType::revolute;
    l.axis = core::Vec3(0.3 * i, 1.0, -0.2 * i);
    l.origin = core::Vec3(0.1, 0.02 * i, 0.0);
    l.com = core::Vec3(0.05, 0.0, 0.01);
    p.links.push_back(l);
  }
  p.gravity = core::Vec3(0, 0, -9.8);
  const components::SpatialTree tree("tree", p);
  const int n = tree.joint_count();
  core::Vec x = core::Vec::LinSpaced(2 * n, -1.0, 1.0), u = core::Vec::Ones(n), x_dot(2 * n);
  const long before = allocations.load();
  for (int k = 0; k < 10; ++k) tree.derivative(x, u, x_dot);
  const long during = allocations.load() - before;
  CHECK(during == 0);
  CHECK(x_dot.allFinite());
  // The counter sees allocations (link_poses returns a vector).
  const auto poses = tree.link_poses(x.head(n));
  CHECK(allocations.load() - before > during);
  CHECK(poses.size() == static_cast<std::size_t>(n));
}
