// URDF mesh visuals (issue 37 item 2): where a mesh file name leads (relative, package://
// through the URDF's folder and the search path, file://), what is refused (a '..' out of
// the folder, a symbolic link out of it, an absolute path elsewhere, other schemes, other
// formats, a missing file), each format read from files written here (ASCII and binary STL,
// OBJ with and without its material library, DAE with node transforms), normals made where
// a file has none, the scene's triangle bound, and a scene naming a bad mesh refused at load
// (exit code 2 from `stiction run --no-video`, naming the URDF and the mesh).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../app/run_stiction.hpp"
#include "scene/mesh_file.hpp"
#include "scene/mesh_path.hpp"
#include "scene/scene.hpp"
#include "scene/urdf_loader.hpp"

using namespace stiction;
using Catch::Contains;
namespace fs = std::filesystem;

namespace {

// A fresh folder per test case: the test's own files, nothing else.
fs::path fresh(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("stiction_test_meshes_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return fs::canonical(d);
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A tetrahedron with corners o, x, y, z (0.1 m edges), faces counter-clockwise outside.
struct Tri {
  float a[3], b[3], c[3];
};
std::vector<Tri> tetrahedron() {
  return {{{0, 0, 0}, {0, 0.1f, 0}, {0.1f, 0, 0}},
          {{0, 0, 0}, {0.1f, 0, 0}, {0, 0, 0.1f}},
          {{0, 0, 0}, {0, 0, 0.1f}, {0, 0.1f, 0}},
          {{0.1f, 0, 0}, {0, 0.1f, 0}, {0, 0, 0.1f}}};
}

std::string ascii_stl(const std::vector<Tri>& tris) {
  std::string s = "solid tet\n";
  for (const Tri& t : tris) {
    s += " facet normal 0 0 0\n  outer loop\n";
    for (const float* v : {t.a, t.b, t.c}) {
      s += "   vertex " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " +
           std::to_string(v[2]) + "\n";
    }
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid tet\n";
}

std::string binary_stl(const std::vector<Tri>& tris) {
  std::string s(80, ' ');
  s.replace(0, 9, "tet model");  // not "solid": a binary file
  const auto n = static_cast<std::uint32_t>(tris.size());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const Tri& t : tris) {
    const float normal[3] = {0, 0, 0};
    s.append(reinterpret_cast<const char*>(normal), 12);
    for (const float* v : {t.a, t.b, t.c}) s.append(reinterpret_cast<const char*>(v), 12);
    s.append(2, '\0');
  }
  return s;
}

// A cube of side 0.2 centred at (1, 2, 3), faces as quads, no normals.
std::string cube_obj(const std::string& mtllib) {
  std::string s = mtllib.empty() ? "" : "mtllib " + mtllib + "\n";
  for (int k = 0; k < 8; ++k) {
    s += "v " + std::to_string(1.0 + ((k & 1) ? 0.1 : -0.1)) + " " +
         std::to_string(2.0 + ((k & 2) ? 0.1 : -0.1)) + " " +
         std::to_string(3.0 + ((k & 4) ? 0.1 : -0.1)) + "\n";
  }
  if (!mtllib.empty()) s += "usemtl paint\n";
  // Corners k = x + 2 y + 4 z (1-based in OBJ); each face counter-clockwise from outside.
  s += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return s;
}

// A DAE with one triangle geometry placed twice by node translations, in red.
std::string two_triangle_dae() {
  const char* geometry = R"(<geometry id="tri"><mesh>
  <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
    <technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles material="paint" count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry>)";
  std::string node =
      R"(<instance_geometry url="#tri"><bind_material><technique_common><instance_material symbol="paint" target="#red"/></technique_common></bind_material></instance_geometry>)";
  return std::string(R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
<library_effects><effect id="red-fx"><profile_COMMON><technique sid="c"><lambert><diffuse><color>0.9 0.1 0.05 1</color></diffuse></lambert></technique></profile_COMMON></effect></library_effects>
<library_materials><material id="red" name="red"><instance_effect url="#red-fx"/></material></library_materials>
<library_geometries>)") +
         geometry + R"(</library_geometries>
<library_visual_scenes><visual_scene id="s">
<node id="a"><translate>0 0 5</translate>)" +
         node + R"(</node>
<node id="b"><translate>0 0 7</translate>)" +
         node + R"(</node>
</visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

std::string mesh_urdf(const std::string& filename, int uses = 1) {
  std::string visuals;
  for (int k = 0; k < uses; ++k) {
    visuals += "<visual><geometry><mesh filename=\"" + filename + "\"/></geometry></visual>";
  }
  return R"(<?xml version="1.0"?><robot name="r"><link name="base"/>
<joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
<link name="arm"><inertial><mass value="1"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial>)" +
         visuals + "</link></robot>\n";
}

scene::TriangleMesh load(const fs::path& file) {
  return scene::load_mesh_file(file, file.parent_path(), scene::kMaxSceneTriangles);
}

}  // namespace

TEST_CASE("mesh paths: relative, package:// and file:// names lead into the folders named",
          "[urdf][meshes]") {
  const fs::path root = fresh("paths");
  // The ROS layout: my_robot/urdf/robot.urdf, my_robot/meshes/a.stl.
  const fs::path urdf = root / "my_robot" / "urdf" / "robot.urdf";
  write(urdf, "");
  write(root / "my_robot" / "urdf" / "parts" / "near.STL", ascii_stl(tetrahedron()));
  write(root / "my_robot" / "meshes" / "a.stl", ascii_stl(tetrahedron()));
  write(root / "shelf" / "tools" / "meshes" / "b.dae", two_triangle_dae());

  const auto near = scene::resolve_mesh_path("parts/near.STL", urdf, {});
  CHECK(near.file == root / "my_robot" / "urdf" / "parts" / "near.STL");
  CHECK(near.folder == root / "my_robot" / "urdf");
  // Not through the URDF folder's parents (never elsewhere than the folders named): the
  // folder holding the package goes on the search path.
  CHECK_THROWS_WITH(scene::resolve_mesh_path("package://my_robot/meshes/a.stl", urdf, {}),
                    Contains("no package folder named 'my_robot'"));
  const auto a = scene::resolve_mesh_path("package://my_robot/meshes/a.stl", urdf, {root});
  CHECK(a.file == root / "my_robot" / "meshes" / "a.stl");
  CHECK(a.folder == root / "my_robot");
  // The URDF's own folder, named as the package or holding it.
  write(root / "my_robot" / "urdf" / "kit" / "c.stl", ascii_stl(tetrahedron()));
  CHECK(scene::resolve_mesh_path("package://urdf/parts/near.STL", urdf, {}).file ==
        root / "my_robot" / "urdf" / "parts" / "near.STL");
  CHECK(scene::resolve_mesh_path("package://kit/c.stl", urdf, {}).file ==
        root / "my_robot" / "urdf" / "kit" / "c.stl");
  // Another package: only through the search path (a folder holding it, or itself).
  CHECK_THROWS_WITH(
      scene::resolve_mesh_path("package://tools/meshes/b.dae", urdf, {}),
      Contains("no package folder named 'tools'") && Contains("STICTION_MESH_PATH is not set"));
  CHECK(scene::resolve_mesh_path("package://tools/meshes/b.dae", urdf, {root / "shelf"}).file ==
        root / "shelf" / "tools" / "meshes" / "b.dae");
  CHECK(scene::resolve_mesh_path("package://tools/meshes/b.dae", urdf, {root / "shelf" / "tools"})
            .folder == root / "shelf" / "tools");
  // The search path from the environment, ':'-separated, empty entries skipped.
  ::setenv("STICTION_MESH_PATH", (":/nonexistent:" + (root / "shelf").string() + ":").c_str(),
           1);
  const std::vector<fs::path> search = scene::package_search_path();
  ::unsetenv("STICTION_MESH_PATH");
  REQUIRE(search.size() == 2);
  CHECK(search[1] == root / "shelf");
  CHECK(scene::resolve_mesh_path("package://tools/meshes/b.dae", urdf, search).file ==
        root / "shelf" / "tools" / "meshes" / "b.dae");
  // file://: inside the URDF's folder or a search folder only.
  const std::string inside =
      "file://" + (root / "my_robot" / "urdf" / "parts" / "near.STL").string();
  CHECK(scene::resolve_mesh_path(inside, urdf, {}).file == near.file);
  const std::string other = "file://" + (root / "shelf" / "tools" / "meshes" / "b.dae").string();
  CHECK_THROWS_WITH(scene::resolve_mesh_path(other, urdf, {}),
                    Contains("an absolute path is read only inside the URDF's folder"));
  CHECK(scene::resolve_mesh_path(other, urdf, {root / "shelf"}).file ==
        root / "shelf" / "tools" / "meshes" / "b.dae");
}

TEST_CASE("mesh paths: escapes, other schemes and formats and missing files are refused",
          "[urdf][meshes]") {
  const fs::path root = fresh("refused");
  const fs::path urdf = root / "robot" / "robot.urdf";
  write(urdf, "");
  write(root / "secret.stl", ascii_stl(tetrahedron()));  // beside the URDF's folder
  write(root / "robot" / "meshes" / "a.stl", ascii_stl(tetrahedron()));
  fs::create_symlink(root / "secret.stl", root / "robot" / "meshes" / "link.stl");
  const auto refused = [&](const std::string& name) {
    try {
      scene::resolve_mesh_path(name, urdf, {});
    } catch (const scene::MeshPathError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused("../secret.stl"), Contains("leaves the URDF's folder"));
  CHECK_THAT(refused("meshes/../../secret.stl"), Contains("leaves the URDF's folder"));
  CHECK_THAT(refused("package://robot/../secret.stl"), Contains("leaves the package folder"));
  CHECK_THAT(refused("package://../secret.stl"), Contains("package://NAME/FILE"));
  CHECK_THAT(refused("package:///secret.stl"), Contains("package://NAME/FILE"));
  CHECK_THAT(refused("meshes/link.stl"), Contains("symbolic link") && Contains("secret.stl"));
  CHECK_THAT(refused((root / "secret.stl").string()), Contains("only inside the URDF's folder"));
  CHECK_THAT(refused("file://" + (root / "secret.stl").string()),
             Contains("only inside the URDF's folder"));
  CHECK_THAT(refused("file://meshes/a.stl"), Contains("file:// needs an absolute path"));
  CHECK_THAT(refused("http://example.invalid/a.stl"), Contains("'http://' is not read"));
  CHECK_THAT(refused("meshes/a.ply"), Contains("'.ply'") && Contains("STL, OBJ or DAE"));
  CHECK_THAT(refused("/etc/passwd"), Contains("no extension"));
  CHECK_THAT(refused(""), Contains("empty"));
  CHECK_THAT(refused("meshes"), Contains("no extension"));
  write(root / "robot" / "folder.stl" / "x", "");
  CHECK_THAT(refused("folder.stl"), Contains("not a regular file"));
  CHECK_THAT(refused("meshes/b.stl"),
             Contains("no file 'meshes/b.stl' in the URDF's folder") && Contains("robot"));
  CHECK(refused("meshes/a.stl") == "accepted");
}

TEST_CASE("mesh files: STL (ASCII and binary), OBJ and DAE read, with normals and colours",
          "[urdf][meshes]") {
  const fs::path dir = fresh("formats");
  SECTION("STL: both encodings give the same outward-lit tetrahedron") {
    write(dir / "ascii.stl", ascii_stl(tetrahedron()));
    write(dir / "binary.stl", binary_stl(tetrahedron()));
    for (const char* name : {"ascii.stl", "binary.stl"}) {
      INFO(name);
      const scene::TriangleMesh m = load(dir / name);
      REQUIRE(m.triangle_count() == 4);
      REQUIRE(m.parts.size() == 1);
      const scene::TriangleMesh::Part& p = m.parts[0];
      CHECK_FALSE(p.has_colour);  // STL has none: the URDF's or grey
      CHECK(p.lower.isApprox(Eigen::Vector3f::Zero()));
      CHECK(p.upper.isApprox(Eigen::Vector3f::Constant(0.1f)));
      // The file's normals are zero: computed, unit and pointing away from the centroid.
      const Eigen::Vector3f centroid = Eigen::Vector3f::Constant(0.025f);
      for (std::size_t k = 0; k < p.indices.size(); k += 3) {
        Eigen::Vector3f face_centre = Eigen::Vector3f::Zero();
        for (int c = 0; c < 3; ++c) face_centre += p.positions[p.indices[k + c]] / 3.0f;
        for (int c = 0; c < 3; ++c) {
          const Eigen::Vector3f& n = p.normals[p.indices[k + c]];
          CHECK(std::abs(n.norm() - 1.0f) < 1e-5f);
          CHECK(n.dot(face_centre - centroid) > 0.0f);
        }
        // The winding agrees with the normal (counter-clockwise outside).
        const Eigen::Vector3f e =
            (p.positions[p.indices[k + 1]] - p.positions[p.indices[k]])
                .cross(p.positions[p.indices[k + 2]] - p.positions[p.indices[k]]);
        CHECK(e.dot(p.normals[p.indices[k]]) > 0.0f);
      }
    }
  }
  SECTION("OBJ: quads split, creased normals made, the colour from its .mtl") {
    write(dir / "cube.obj", cube_obj("cube.mtl"));
    write(dir / "cube.mtl", "newmtl paint\nKd 0.1 0.7 0.2\n");
    const scene::TriangleMesh m = load(dir / "cube.obj");
    REQUIRE(m.triangle_count() == 12);
    REQUIRE(m.parts.size() == 1);
    const scene::TriangleMesh::Part& p = m.parts[0];
    CHECK(p.centre().isApprox(Eigen::Vector3f(1.0f, 2.0f, 3.0f)));
    CHECK(p.half_extent().isApprox(Eigen::Vector3f::Constant(0.1f)));
    REQUIRE(p.has_colour);
    CHECK(p.rgba.head<3>().isApprox(Eigen::Vector3d(0.1, 0.7, 0.2), 1e-6));
    // Faces meet at 90 degrees, over the 60 degree smoothing bound: each corner of each face
    // has that face's normal, one of the six axis directions, pointing out of the cube.
    for (std::size_t v = 0; v < p.positions.size(); ++v) {
      const Eigen::Vector3f& n = p.normals[v];
      CHECK(n.cwiseAbs().maxCoeff() > 0.9999f);
      CHECK(n.dot(p.positions[v] - p.centre()) > 0.0f);
    }
  }
  SECTION("OBJ: a material library outside the mesh's folder is not read") {
    write(dir / "outside.mtl", "newmtl paint\nKd 0.1 0.7 0.2\n");
    write(dir / "inner" / "cube.obj", cube_obj("../outside.mtl"));
    const scene::TriangleMesh m = load(dir / "inner" / "cube.obj");  // folder: inner/
    REQUIRE(m.triangle_count() == 12);
    // assimp names the material after `usemtl` with its own grey: not the outside file's green.
    CHECK_FALSE(m.parts[0].rgba.head<3>().isApprox(Eigen::Vector3d(0.1, 0.7, 0.2), 1e-3));
    CHECK(m.parts[0].rgba.head<3>().isApprox(Eigen::Vector3d(0.6, 0.6, 0.6), 1e-3));
  }
  SECTION("DAE: node transforms applied, up axis as written, the material's colour") {
    write(dir / "two.dae", two_triangle_dae());
    const scene::TriangleMesh m = load(dir / "two.dae");
    REQUIRE(m.triangle_count() == 2);
    REQUIRE(m.parts.size() == 1);
    const scene::TriangleMesh::Part& p = m.parts[0];
    CHECK(p.lower.isApprox(Eigen::Vector3f(0.0f, 0.0f, 5.0f)));
    CHECK(p.upper.isApprox(Eigen::Vector3f(1.0f, 1.0f, 7.0f)));
    REQUIRE(p.has_colour);
    CHECK(p.rgba.head<3>().isApprox(Eigen::Vector3d(0.9, 0.1, 0.05), 1e-6));
    // Flat in z: the drawn box keeps a non-zero thickness.
    CHECK(p.half_extent().z() == Approx(1.0f));
    for (const Eigen::Vector3f& n : p.normals) CHECK(n.z() == Approx(1.0f));
  }
  SECTION("what is not a mesh is an error, not an empty picture") {
    write(dir / "empty.stl", "");
    write(dir / "text.obj", "this is not a mesh\n");
    CHECK_THROWS_AS(load(dir / "empty.stl"), scene::MeshFileError);
    CHECK_THROWS_WITH(load(dir / "text.obj"), Contains("no triangles") || Contains("cannot read"));
  }
}

TEST_CASE("mesh files: the scene's triangle bound, per file and over every use", "[urdf][meshes]") {
  const fs::path dir = fresh("bound");
  // 1000 triangles in one binary STL: a fan of thin triangles.
  std::vector<Tri> fan;
  for (int k = 0; k < 1000; ++k) {
    const float a = 0.006f * static_cast<float>(k), b = 0.006f * static_cast<float>(k + 1);
    fan.push_back({{0, 0, 0}, {std::cos(a), std::sin(a), 0}, {std::cos(b), std::sin(b), 0}});
  }
  write(dir / "fan.stl", binary_stl(fan));
  CHECK(load(dir / "fan.stl").triangle_count() == 1000);
  CHECK_THROWS_WITH(scene::load_mesh_file(dir / "fan.stl", dir, 999),
                    Contains("it has 1000 triangles") && Contains("999 left") &&
                        Contains(std::to_string(scene::kMaxSceneTriangles)));
  // 200 uses fit the bound of 200000 exactly; a 201st does not.
  const std::size_t fit = scene::kMaxSceneTriangles / 1000;
  write(dir / "fits.urdf", mesh_urdf("fan.stl", static_cast<int>(fit)));
  const scene::UrdfRobot robot = scene::load_urdf(dir / "fits.urdf");
  REQUIRE(robot.visuals.size() == fit);
  CHECK(robot.visuals[0].triangles == robot.visuals[fit - 1].triangles);  // read once
  write(dir / "over.urdf", mesh_urdf("fan.stl", static_cast<int>(fit) + 1));
  CHECK_THROWS_WITH(scene::load_urdf(dir / "over.urdf"),
                    Contains("over.urdf: link 'arm': mesh 'fan.stl'") &&
                        Contains("bound of " + std::to_string(scene::kMaxSceneTriangles)));
}

TEST_CASE("a scene whose URDF names a bad mesh is refused at load, naming the URDF and mesh",
          "[urdf][meshes]") {
  const fs::path dir = fresh("scene");
  write(dir / "meshes" / "tet.stl", ascii_stl(tetrahedron()));
  const std::string scene_text =
      "name = \"m\"\n[simulation]\nduration = 0.01\n[bodies.arm]\ntype = \"urdf\"\n"
      "file = \"robot.urdf\"\n";
  write(dir / "m.toml", scene_text);

  write(dir / "robot.urdf", mesh_urdf("meshes/tet.stl"));
  const scene::Scene good = scene::load_scene(scene::SceneSource((dir / "m.toml").string()));
  REQUIRE(good.drawing.bodies.size() == 1);
  const scene::UrdfVisual& v = good.drawing.bodies[0].visuals.at(0);
  CHECK(v.mesh_file == dir / "meshes" / "tet.stl");
  REQUIRE(v.triangles);
  CHECK(v.triangles->triangle_count() == 4);

  for (const char* bad : {"meshes/missing.stl", "../../../../etc/passwd.stl"}) {
    INFO(bad);
    write(dir / "robot.urdf", mesh_urdf(bad));
    CHECK_THROWS_WITH(scene::load_scene(scene::SceneSource((dir / "m.toml").string())),
                      Contains("m.toml:6:") &&
                          Contains("robot.urdf: link 'arm': mesh '" + std::string(bad) + "'"));
    // `run` without a video refuses it before simulating, as other bad input (exit code 2).
    const testing::Outcome o =
        testing::run_stiction({"run", (dir / "m.toml").string(), "--no-video", "--no-plots",
                               "--out", (dir / "out").string()},
                              dir);
    CHECK(o.code == 2);
    CHECK_THAT(o.out, Contains("robot.urdf: link 'arm': mesh '" + std::string(bad) + "'"));
    CHECK_FALSE(fs::exists(dir / "out" / "trajectory.csv"));
  }
}
