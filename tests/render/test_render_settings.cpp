#include <catch2/catch.hpp>

#include "render/render_settings.hpp"
#include "scene/toml_reader.hpp"

using namespace stiction;
using namespace stiction::render;

namespace {

RenderSettings read(const std::string& text) {
  return read_render_settings(toml::parse(std::string_view(text), std::string_view("scene.toml")), {"sphere", "arm"},
                              {"t", "sphere.p.x", "sphere.p.y", "sphere.p.z", "contact.slip.x",
                               "contact.slip.y", "contact.slip.z", "contact.n_force"});
}

}  // namespace

TEST_CASE("render settings: defaults and values", "[render][settings]") {
  const RenderSettings d = read("");
  CHECK(d.width == 1280);
  CHECK(d.height == 720);
  CHECK(d.fps == 60.0);
  CHECK(d.msaa == 4);
  CHECK(d.codec == "h264");
  const RenderSettings s = read(
      "[render]\nsize = [640, 360]\nfps = 30\ncrf = 23\nslow_motion = 4\nmsaa = 1\n"
      "shadow_map_size = 1024\n[camera]\nposition = [1, -3, 1]\ntarget = [0, 0, 0.2]\nfov = 30\n"
      "follow = \"sphere\"\n[overlay]\nsignal = \"contact.slip\"\nunit = \"m/s\"\ntrail = true\n");
  CHECK(s.width == 640);
  CHECK(s.height == 360);
  CHECK(s.fps == 30.0);
  CHECK(s.crf == 23);
  CHECK(s.slow_motion == 4.0);
  CHECK(s.msaa == 1);
  CHECK(s.shadow_map_size == 1024);
  REQUIRE(s.camera.position);
  CHECK(s.camera.position->y() == -3.0);
  CHECK(s.camera.fov_degrees == 30.0);
  CHECK(s.camera.follow == "sphere");
  CHECK_FALSE(s.camera.follow_vertical);
  CHECK(read("[camera]\nfollow = \"sphere\"\nfollow_vertical = true\n").camera.follow_vertical);
  CHECK(s.overlay.signal == "contact.slip");
  CHECK(s.overlay.label == "contact.slip");
  CHECK(s.overlay.trail);
  CHECK(read("[overlay]\nsignal = \"contact.n_force\"\n").overlay.signal == "contact.n_force");
}

TEST_CASE("render settings: bad input is an InputError at FILE:LINE:COL", "[render][settings]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(read("[render]\nsize = [641, 360]\n"), Contains("scene.toml:2:") && Contains("even"));
  CHECK_THROWS_WITH(read("[render]\nsize = [0, 360]\n"), Contains("render.size"));
  CHECK_THROWS_WITH(read("[render]\ncodec = \"vp9\"\n"), Contains("unknown codec 'vp9'"));
  CHECK_THROWS_WITH(read("[render]\nfsp = 30\n"), Contains("scene.toml:2:1") && Contains("unknown key 'render.fsp'"));
  CHECK_THROWS_WITH(read("[render]\nmsaa = 8\n"), Contains("render.msaa"));
  CHECK_THROWS_WITH(read("[render]\nshadow_map_size = 1000\n"), Contains("power of two"));
  CHECK_THROWS_WITH(read("[render]\nfps = 0\n"), Contains("render.fps"));
  CHECK_THROWS_WITH(read("[camera]\nfollow = \"ball\"\n"), Contains("no body named 'ball'"));
  CHECK_THROWS_WITH(read("[camera]\nzoom = 2\n"), Contains("unknown key 'camera.zoom'"));
  CHECK_THROWS_WITH(read("[camera]\nfollow_vertical = true\n"),
                    Contains("scene.toml:2:") && Contains("camera.follow_vertical") && Contains("needs `follow`"));
  CHECK_THROWS_WITH(read("[camera]\nfollow = \"sphere\"\nfollow_vertical = 1\n"),
                    Contains("camera.follow_vertical"));
  CHECK_THROWS_WITH(read("[overlay]\nsignal = \"contact.slp\"\n"), Contains("no signal named"));
  CHECK_THROWS_WITH(read("[overlay]\nsignal = \"contact\"\n"), Contains("no signal named"));
  CHECK_THROWS_AS(read("render = 3\n"), scene::InputError);
}
