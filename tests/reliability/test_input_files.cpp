// Files the user names are checked before they are read (issue 39): a scene or URDF `file`
// that is a FIFO, a device or a directory, or larger than the documented bound, is refused
// with exit 2 naming the file, at once: never a hang on the FIFO, never a read of /dev/zero
// until the memory runs out.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "child.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

fs::path scratch(const std::string& name) { return scratch_dir("input_files", name); }

// A scene whose one body is a URDF robot read from `file`.
fs::path urdf_scene(const fs::path& dir, const std::string& file) {
  const fs::path scene = dir / "robot.toml";
  std::ofstream(scene) << "name = \"robot\"\n[simulation]\nduration = 0.01\n"
                       << "[bodies.arm]\ntype = \"urdf\"\nfile = \"" << file << "\"\n";
  return scene;
}

// `stiction ARGS` ends within 20 s (a hang on a FIFO would not) with exit 2, naming `what`.
void refused(const std::vector<std::string>& args, const fs::path& dir, const std::string& what,
             const std::string& why) {
  Child child(args, dir, "refused");
  const int code = child.wait(std::chrono::seconds(20));
  INFO(child.err());
  CHECK(code == 2);
  CHECK_THAT(child.err(), Contains(what));
  CHECK_THAT(child.err(), Contains(why));
}

}  // namespace

TEST_CASE("a scene file that is a FIFO, a directory or too large is refused at once",
          "[input_files]") {
  const fs::path dir = scratch("scene");
  REQUIRE(::mkfifo((dir / "pipe.toml").c_str(), 0644) == 0);
  refused({"run", "pipe.toml", "--out", "o"}, dir, "pipe.toml", "FIFO");
  refused({"check", "pipe.toml"}, dir, "pipe.toml", "FIFO");
  fs::create_directory(dir / "folder.toml");
  refused({"check", "folder.toml"}, dir, "folder.toml", "a directory");
  // A sparse file of 65 MiB: refused from its size, before a byte is read.
  {
    std::ofstream big(dir / "big.toml");
  }
  fs::resize_file(dir / "big.toml", 65u << 20);
  refused({"check", "big.toml"}, dir, "big.toml", "above the 64 MiB");
}

TEST_CASE("a URDF file that is a FIFO, /dev/zero or a directory is refused at its key",
          "[input_files]") {
  const fs::path dir = scratch("urdf");
  REQUIRE(::mkfifo((dir / "robot.urdf").c_str(), 0644) == 0);
  urdf_scene(dir, "robot.urdf");
  refused({"check", "robot.toml"}, dir, "robot.toml:", "FIFO");
  urdf_scene(dir, "/dev/zero");
  refused({"run", "robot.toml", "--out", "o"}, dir, "/dev/zero", "character device");
  urdf_scene(dir, "/etc");
  refused({"check", "robot.toml"}, dir, "/etc", "a directory");
  CHECK_FALSE(fs::exists(dir / "o"));
}

TEST_CASE("names from a file are echoed with their control characters escaped",
          "[input_files]") {
  // A URDF joint named with an OSC sequence (which retitles a terminal) and a CSI colour: the
  // error names the joint, and stderr holds no escape byte.
  const fs::path dir = scratch("escapes");
  std::ofstream(dir / "robot.urdf")
      << "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>"
      << "<joint name=\"j\x1b]0;pwned\x07\x1b[31m\" type=\"floating\"><parent link=\"a\"/>"
      << "<child link=\"b\"/></joint></robot>";
  urdf_scene(dir, "robot.urdf");
  const RunResult r = run_child({"check", "robot.toml"}, dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("floating"));
  CHECK_THAT(r.err, Contains("j\\x1b]0;pwned\\x07\\x1b[31m"));
  CHECK(r.err.find('\x1b') == std::string::npos);
  CHECK(r.err.find('\x07') == std::string::npos);
}
