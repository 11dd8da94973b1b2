// Builds a URDF robot and the scene that loads it from fuzzer bytes (fuzz/fuzz_urdf.cpp,
// issue 39 item 8): a chain or a tree of links (up to 4095 joints now and then) of every
// joint kind, with `<limit>` (lower above upper, equal, non-numbers, decimal commas),
// `<dynamics>`, odd `<inertia>` (negative, not positive definite, breaking the triangle
// inequality, huge, "nan", "1,5e-3"), odd axes, and `<visual>` / `<collision>` meshes whose
// `filename` is a package:// path, a traversal (../../etc/passwd), an absolute path, a
// device, a URL, or carries control characters and terminal escapes. The scene names the
// URDF as `fuzz.urdf` (next to it) and sets joint friction, limits and a torque source.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz/pairs_recipe.hpp"
#include "fuzz/toml_structure.hpp"

namespace stiction::fuzz {

namespace urdf {

inline constexpr std::string_view kJointTypes[] = {"revolute", "continuous", "prismatic", "fixed"};
inline constexpr std::string_view kOddJointTypes[] = {"floating", "planar", "bogus", ""};

inline constexpr std::string_view kNumbers[] = {
    "0",   "1",    "-1",  "0.5",    "3.14159", "-3.14159", "1e308",  "-1e308", "nan",
    "inf", "-inf", "abc", "1,5e-3", "1.5e-3",  "5e-324",   "1e-300", "",       " ",
    "1 2", "0x10", "+1",  "1e",     "--1",     "1e400",    "2.5",    "100",    "-0"};

inline constexpr std::string_view kAxes[] = {"0 0 1", "1 0 0", "0 1 0", "1 1 1", "0 0 -1"};
inline constexpr std::string_view kOddAxes[] = {"0 0 0", "nan 0 1", "1e308 1e308 0", "1e-320 0 0",
                                                "0 0",   "0 0 1 0", "a b c"};

inline constexpr std::string_view kInertias[] = {
    R"(ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3")",
    R"(ixx="1.3e-5" ixy="0" ixz="0" iyy="6.7e-4" iyz="0" izz="6.7e-4")"};
inline constexpr std::string_view kOddInertias[] = {
    R"(ixx="-1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3")",
    R"(ixx="1e-3" ixy="5e-3" ixz="0" iyy="1e-3" iyz="0" izz="1e-3")",
    R"(ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="5e-3")",
    R"(ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0")",
    R"(ixx="1e300" ixy="0" ixz="0" iyy="1e300" iyz="0" izz="1e300")",
    R"(ixx="1e-300" ixy="0" ixz="0" iyy="1e-300" iyz="0" izz="1e-300")",
    R"(ixx="nan" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3")",
    R"(ixx="1,5e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3")",
    R"(ixx="abc" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3")",
    R"(ixx="1e-3" iyy="1e-3")",
    R"(ixx="1e-3" ixy="1e-3" ixz="1e-3" iyy="1e-3" iyz="1e-3" izz="1e-3")"};

// Mesh file names: what a robot description holds, and what a hostile one could.
inline constexpr std::string_view kMeshes[] = {"package://robot/meshes/link.stl",
                                               "meshes/link.dae",
                                               "package://../../../../etc/passwd",
                                               "../../etc/passwd",
                                               "../../../../../../../../etc/shadow",
                                               "/etc/passwd",
                                               "/dev/zero",
                                               "/dev/stdin",
                                               "/proc/self/environ",
                                               "file:///etc/passwd",
                                               "http://example.invalid/mesh.stl",
                                               "package://",
                                               "package:///etc/passwd",
                                               "fuzz.urdf",
                                               "fuzz.toml",
                                               ".",
                                               "",
                                               "meshes/\x1b[31mred\x1b[0m.stl",
                                               "\x1b]0;title\x07\x1b[2J",
                                               "a&#10;b&#13;c.stl",
                                               "&#x1b;[31m.stl",
                                               "nul&#0;.stl",
                                               "%2e%2e/%2e%2e/etc/passwd",
                                               "meshes/..\\..\\windows\\win.ini",
                                               "~/.ssh/id_rsa",
                                               "$HOME/.bashrc"};

// From `good`, or from `odd` when the byte says hostile (pairs::hostile_from()).
template <std::size_t N, std::size_t M>
std::string_view pick(ByteReader& in, const std::string_view (&good)[N],
                      const std::string_view (&odd)[M]) {
  const std::uint8_t b = in.byte();
  return b < pairs::hostile_from() ? good[b % N] : odd[b % M];
}

}  // namespace urdf

inline std::string urdf_robot(ByteReader& in) {
  using namespace urdf;
  const auto value = [&in]() { return std::string(in.pick(kNumbers)); };
  const auto num = [&in, &value](std::string_view plain) {
    return in.byte() < pairs::hostile_from() ? std::string(plain) : value();
  };
  std::string x = "<?xml version=\"1.0\"?>\n<robot name=\"fuzz\">\n";
  const auto visual = [&](const char* element) {
    x += "  <";
    x += element;
    x += ">";
    if (in.byte() < 128) x += "<origin xyz=\"0 0 " + num("0.1") + "\" rpy=\"0 0 0\"/>";
    x += "<geometry>";
    const std::uint8_t g = in.byte();
    if (g < 140) {
      const std::string_view mesh = in.pick(kMeshes);
      // An escape byte raw in the attribute (tinyxml reads it), or as the text was.
      x += "<mesh filename=\"" + std::string(mesh) + "\"";
      if (in.byte() < 64) x += " scale=\"" + num("1") + " 1 1\"";
      x += "/>";
    } else if (g < 180) {
      x += "<box size=\"" + num("0.1") + " 0.02 0.02\"/>";
    } else if (g < 220) {
      x += "<cylinder radius=\"" + num("0.02") + "\" length=\"0.1\"/>";
    } else {
      x += "<sphere radius=\"" + num("0.03") + "\"/>";
    }
    x += "</geometry></";
    x += element;
    x += ">\n";
  };
  // Links: a chain, or a tree whose parents the bytes choose.
  const std::uint8_t shape = in.byte();
  const std::size_t joints = shape < 240 ? 1 + in.byte() % 8 : 1 + in.size(4094);
  const bool tree = (shape & 1) != 0;
  x += "<link name=\"base\"/>\n";
  for (std::size_t i = 1; i <= joints; ++i) {
    const std::string link = pairs::named("l", i);
    x += "<link name=\"" + link + "\">\n";
    const std::uint8_t parts = in.byte();
    if ((parts & 3) != 0 || in.byte() < pairs::hostile_from()) {  // massless only when hostile
      x += "  <inertial><origin xyz=\"" + num("0.1") + " 0 0\" rpy=\"0 0 0\"/><mass value=\"" +
           num("0.2") + "\"/><inertia " + std::string(pick(in, kInertias, kOddInertias)) +
           "/></inertial>\n";
    }
    if (parts & 4) visual("visual");
    if (parts & 8) visual("collision");
    if (parts & 16) visual("visual");
    x += "</link>\n";
    std::string parent = "base";
    if (i > 1)
      parent = tree ? (in.byte() % i == 0 ? "base" : pairs::named("l", 1 + in.byte() % (i - 1)))
                    : pairs::named("l", i - 1);
    const std::string_view type =
        joints > 64 ? std::string_view("revolute") : pick(in, kJointTypes, kOddJointTypes);
    x += "<joint name=\"" + pairs::named("j", i) + "\" type=\"" + std::string(type) + "\">";
    x += "<parent link=\"" + parent + "\"/><child link=\"" + link + "\"/>";
    x += "<origin xyz=\"" + num("0.2") + " 0 0\" rpy=\"0 " + num("0") + " 0\"/>";
    x += "<axis xyz=\"" +
         std::string(joints > 64 ? std::string_view("0 0 1") : pick(in, kAxes, kOddAxes)) + "\"/>";
    const std::uint8_t limit = in.byte() < pairs::hostile_from() ? in.byte() % 200 : in.byte();
    if (limit < 170) {
      x += "<limit lower=\"" + num("-1.0") + "\" upper=\"" + num("1.0") + "\" effort=\"" +
           num("10") + "\" velocity=\"" + num("2") + "\"/>";
    } else if (limit < 200) {
      x += "<limit effort=\"10\" velocity=\"2\"/>";  // lower == upper == 0: no travel limit
    } else if (limit < 215) {
      x += "<limit lower=\"1.0\" upper=\"-1.0\" effort=\"10\" velocity=\"2\"/>";
    }
    if (in.byte() < 128) {
      x += "<dynamics friction=\"" + num("0.2") + "\" damping=\"" + num("0.01") + "\"/>";
    }
    x += "</joint>\n";
  }
  x += "</robot>\n";
  return x;
}

// The scene that loads `fuzz.urdf`, with the joint keys of a urdf body.
// Chooses the input's hostility (pairs::choose_hostility) for itself and the robot after it.
inline std::string urdf_scene(ByteReader& in) {
  pairs::choose_hostility(in);
  const std::string_view integrator = in.pick(pairs::kIntegrators);
  std::string doc = "name = \"fuzz_urdf\"\n[simulation]\nintegrator = ";
  doc += std::string(integrator);
  doc += "\ndt = " + pairs::number(in, "1e-4") + "\nduration = 0.5\n";
  if (integrator == "\"rk4_adaptive\"" || integrator == "\"sdirk2\"" ||
      integrator == "\"sdirk4\"") {
    doc += "tolerance = " + pairs::number(in, "1e-6") + "\n";
  }
  doc += "[bodies.arm]\ntype = \"urdf\"\nfile = \"fuzz.urdf\"\n";
  const std::uint8_t keys = in.byte();
  if (keys & 1) doc += "base = " + pairs::vec3(in) + "\n";
  if (keys & 2) doc += "base_rpy = [0.3, " + pairs::number(in, "-0.7") + ", 1.9]\n";
  if (keys & 4 && in.byte() >= pairs::hostile_from()) {
    doc += "angles = [" + pairs::number(in, "0.4") + ", -1.2]\n";  // one per joint or refused
  }
  if (keys & 8) doc += "friction_stiffness = " + pairs::number(in, "5000.0") + "\n";
  if (keys & 16) doc += "limit_stiffness = " + pairs::number(in, "1e4") + "\n";
  if (keys & 32) doc += "limit_damping = " + pairs::number(in, "1.0") + "\n";
  if (keys & 64) {
    doc += "[impedances.motor]\ntype = \"torque_source\"\nbody = \"arm\"\njoint = " +
           std::to_string(in.byte() % 4) + "\ntorque = \"0.3*sin(10*t)\"\n";
  }
  return doc;
}

}  // namespace stiction::fuzz
