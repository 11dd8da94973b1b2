// Fast start: the `stiction` program does not link the rendering stack (OSMesa, LLVM, libav);
// it loads the render plugin only when a run renders.
#include <cstdio>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "child.hpp"
#include "generated_scene.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace stiction::testing;

namespace {

std::string command_output(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  ::pclose(pipe);
  return out;
}

}  // namespace

TEST_CASE("the program links no rendering library", "[fast_start]") {
  const std::string libraries = command_output(std::string("ldd '") + STICTION_BINARY + "'");
  REQUIRE_THAT(libraries, Contains("libc.so"));
  for (const char* heavy : {"libOSMesa", "libLLVM", "libavcodec", "libavformat", "libswscale"}) {
    INFO(heavy);
    CHECK(libraries.find(heavy) == std::string::npos);
  }
}

TEST_CASE("the renderer is loaded only when a run renders", "[fast_start]") {
  const fs::path dir = fs::temp_directory_path() / ("stiction_fast_start_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  SceneSpec spec;
  spec.duration = 0.1;
  spec.extra = "[render]\nsize = [32, 32]\nfps = 10\nmsaa = 1\nshadow_map_size = 0\n";
  const fs::path scene = write_scene(dir, spec);
  // With the plugin pointed elsewhere ($STICTION_RENDER_PLUGIN is then the only place looked
  // at), everything but rendering still works...
  ::setenv("STICTION_RENDER_PLUGIN", (dir / "missing.so").c_str(), 1);
  const std::string quoted_binary = std::string("'") + STICTION_BINARY + "'";
  const std::string no_video = command_output("cd '" + dir.string() + "' && " + quoted_binary + " run '" +
                                              scene.string() + "' --no-video --no-plots --out a 2>&1; echo exit=$?");
  CHECK_THAT(no_video, Contains("exit=0"));
  // ...and a run that renders says what it could not load.
  const std::string video = command_output("cd '" + dir.string() + "' && " + quoted_binary + " run '" + scene.string() +
                                           "' --no-plots --out b 2>&1; echo exit=$?");
  CHECK_THAT(video, Contains("cannot load the renderer"));
  CHECK_THAT(video, Contains("exit=1"));
  ::unsetenv("STICTION_RENDER_PLUGIN");
  // The real binary finds its plugin and renders.
  const std::string real = command_output("cd '" + dir.string() + "' && " + quoted_binary + " run '" +
                                          scene.string() + "' --no-plots --out c 2>&1; echo exit=$?");
  CHECK_THAT(real, Contains("exit=0"));
  CHECK(fs::file_size(dir / "c" / "video.mp4") > 0);
  fs::remove_all(dir);
}
