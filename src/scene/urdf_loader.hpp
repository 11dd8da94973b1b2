// Reads a URDF robot (liburdfdom) into the parameters of a components::SpatialTree plus
// what the scene builds around it: per joint the <dynamics friction damping>, per link
// the visual primitives for drawing.
// Read: links and <inertial> (origin xyz rpy, mass, inertia tensor), joints of type
// revolute, continuous and prismatic (origin xyz rpy, axis, <limit lower upper>,
// <dynamics>), <visual> box, cylinder, sphere and mesh (with its scale) with their origins
// and <material><color>; load_urdf reads the meshes' files too (read_urdf_meshes). A fixed
// joint merges its child link into the parent: mass, centre of mass and inertia
// (parallel-axis theorem) and visuals; links fixed to the root are part of the base (their
// mass plays no part). Refused: floating and planar joints.
// Not read: collisions, transmissions, mimic joints, safety controllers, effort and
// velocity limits, textures.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "components/admittance/spatial_tree.hpp"
#include "scene/drawing.hpp"  // UrdfVisual
#include "scene/mesh_file.hpp"  // kMaxSceneTriangles

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

// `origin` names the text in messages (its file). Mesh visuals keep their file name only.
UrdfRobot parse_urdf(const std::string& text, const std::string& origin);
// Reads the file and its meshes (with the search path of STICTION_MESH_PATH), at most
// `max_triangles` for all of them.
UrdfRobot load_urdf(const std::filesystem::path& file,
                    std::size_t max_triangles = kMaxSceneTriangles);
// Finds (scene/mesh_path.hpp) and reads (scene/mesh_file.hpp) the file of every mesh
// visual of a robot read from `urdf_file`, each file once; a mesh that cannot be found,
// escapes its folders, cannot be read, or takes the meshes past `max_triangles` triangles is
// a UrdfError naming the URDF file, the link and the mesh.
void read_urdf_meshes(UrdfRobot& robot, const std::filesystem::path& urdf_file,
                      const std::vector<std::filesystem::path>& search,
                      std::size_t max_triangles);

}  // namespace stiction::scene
