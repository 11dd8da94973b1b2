// Reads a URDF robot (liburdfdom) into the parameters of a components::SpatialTree plus
// what the scene builds around it: per joint the <dynamics friction damping>, per link
// the visual primitives for drawing.
// Read: links and <inertial> (origin xyz rpy, mass, inertia tensor), joints of type
// revolute, continuous and prismatic (origin xyz rpy, axis, <limit lower upper>,
// <dynamics>), <visual> box, cylinder, sphere and mesh (file name only) with their origins
// and <material><color>. A fixed joint merges its child link into the parent: mass, centre
// of mass and inertia (parallel-axis theorem) and visuals; links fixed to the root are
// part of the base (their mass plays no part). Refused: floating and planar joints.
// Not read: collisions, transmissions, mimic joints, safety controllers, effort and
// velocity limits, textures.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "components/admittance/spatial_tree.hpp"
#include "scene/drawing.hpp"  // UrdfVisual

namespace stiction::scene {

// A URDF that cannot be read or is refused. The message starts with "FILE:" (and
// "FILE:LINE:" when the XML is malformed and the parser knows where).
class UrdfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct UrdfJointDynamics {
  double friction = 0.0;  // Coulomb level (Nm or N)
  double damping = 0.0;   // viscous (Nms/rad or Ns/m)
};

struct UrdfRobot {
  std::string name;
  std::vector<components::SpatialLink> links;  // in the tree's order (parents first)
  std::vector<UrdfJointDynamics> dynamics;     // one per link (its joint)
  std::vector<UrdfVisual> visuals;
};

// `origin` names the text in messages (its file).
UrdfRobot parse_urdf(const std::string& text, const std::string& origin);
UrdfRobot load_urdf(const std::filesystem::path& file);

}  // namespace stiction::scene
