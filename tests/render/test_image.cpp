#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include "image/compare.hpp"
#include "image/png.hpp"

namespace fs = std::filesystem;
using namespace stiction::image;

namespace {

fs::path scratch_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("stiction_test_image_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.set(x, y, {std::uint8_t(x * 255 / (w - 1)), std::uint8_t(y * 255 / (h - 1)),
                     std::uint8_t((x + y) % 256), std::uint8_t(200 + x % 50)});
  return img;
}

}  // namespace

TEST_CASE("PNG round trip is lossless at both speeds", "[image]") {
  const fs::path dir = scratch_dir("roundtrip");
  const Image img = gradient(37, 23);
  for (PngSpeed speed : {PngSpeed::fast, PngSpeed::small}) {
    write_png(dir / "a.png", img, speed);
    const Image back = read_png(dir / "a.png");
    CHECK(back.width == 37);
    CHECK(back.height == 23);
    CHECK(back.pixels == img.pixels);
  }
  // Atomic write: no temporary file is left behind.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    (void)entry;
    ++files;
  }
  CHECK(files == 1);
}

TEST_CASE("PNG errors name the file", "[image]") {
  const fs::path dir = scratch_dir("errors");
  CHECK_THROWS_WITH(read_png(dir / "missing.png"), Catch::Contains("missing.png"));
  CHECK_THROWS_AS(write_png(dir / "no_such_dir" / "x.png", gradient(4, 4)), ImageError);
  CHECK_FALSE(fs::exists(dir / "no_such_dir"));
}

TEST_CASE("flip_vertical mirrors rows", "[image]") {
  Image img = gradient(5, 4);
  const Rgba top = img.at(2, 0);
  img.flip_vertical();
  CHECK(img.at(2, 3) == top);
}

TEST_CASE("compare counts pixels off by more than the tolerance", "[image]") {
  const Image a = gradient(100, 100);
  Image b = a;
  // 5 is within tolerance 5, 6 is not.
  b.data(0, 0)[0] = static_cast<std::uint8_t>(a.data(0, 0)[0] + 5);
  CompareResult r = compare_images(a, b, {5, 0.0});
  CHECK(r.matches);
  CHECK(r.max_channel_difference == 5);
  b.data(1, 0)[2] = static_cast<std::uint8_t>(a.data(1, 0)[2] ^ 0x40);
  r = compare_images(a, b, {5, 0.0});
  CHECK_FALSE(r.matches);
  CHECK(r.pixels_off == 1);
  // 1 pixel of 10000 is 0.01%: within 0.1%, not within 0.005%.
  CHECK(compare_images(a, b, {5, 0.001}).matches);
  CHECK_FALSE(compare_images(a, b, {5, 0.00005}).matches);
  CHECK(compare_images(a, gradient(100, 99)).size_mismatch);
}

TEST_CASE("compare_to_golden writes expected, actual and diff on failure", "[image]") {
  if (std::getenv("STICTION_UPDATE_GOLDEN")) return;  // this test checks the failure path
  const fs::path dir = scratch_dir("golden");
  const Image a = gradient(64, 32);
  write_png(dir / "g.png", a, PngSpeed::small);
  CHECK(compare_to_golden(dir / "g.png", a, dir / "failed").matches);
  CHECK_FALSE(fs::exists(dir / "failed" / "g.diff.png"));

  Image b = a;
  for (int x = 0; x < 10; ++x) b.set(x, 5, {255, 0, 255, 255});
  const CompareResult r = compare_to_golden(dir / "g.png", b, dir / "failed");
  CHECK_FALSE(r.matches);
  CHECK(read_png(dir / "failed" / "g.expected.png").pixels == a.pixels);
  CHECK(read_png(dir / "failed" / "g.actual.png").pixels == b.pixels);
  const Image diff = read_png(dir / "failed" / "g.diff.png");
  CHECK(diff.at(3, 5).r >= 128);
  CHECK(diff.at(3, 5).g == 0);

  const CompareResult missing = compare_to_golden(dir / "none.png", a, dir / "failed");
  CHECK_FALSE(missing.matches);
  CHECK(fs::exists(dir / "failed" / "none.actual.png"));
}
