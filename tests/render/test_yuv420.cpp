// RGBA -> yuv420p (BT.709, limited range, chroma sited left) against the definition in
// double precision, on primaries and on random images of random even sizes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "image/yuv420.hpp"

using namespace stiction::image;

namespace {

struct Planes {
  int width, height;
  std::vector<std::uint8_t> y, u, v;
  // Strides wider than the rows, as libav pads them.
  int y_stride, c_stride;
  Planes(int w, int h)
      : width(w), height(h), y_stride(w + 32), c_stride(w / 2 + 16) {
    y.assign(static_cast<std::size_t>(y_stride) * h, 0);
    u.assign(static_cast<std::size_t>(c_stride) * (h / 2), 0);
    v.assign(u.size(), 0);
  }
  Yuv420Planes view() { return {y.data(), y_stride, u.data(), c_stride, v.data(), c_stride}; }
  int Y(int x, int yy) const { return y[static_cast<std::size_t>(yy) * y_stride + x]; }
  int U(int i, int j) const { return u[static_cast<std::size_t>(j) * c_stride + i]; }
  int V(int i, int j) const { return v[static_cast<std::size_t>(j) * c_stride + i]; }
};

Planes convert(const Image& image) {
  Planes p(image.width, image.height);
  rgba_to_yuv420_bt709(image, p.view());
  return p;
}

// The definition (Rec. ITU-R BT.709, limited range), in double precision.
constexpr double kKr = 0.2126, kKb = 0.0722, kKg = 1.0 - kKr - kKb;
double luma(double r, double g, double b) {
  return 16.0 + 219.0 / 255.0 * (kKr * r + kKg * g + kKb * b);
}
double cb(double r, double g, double b) {
  return 128.0 + 224.0 / 255.0 * (b - (kKr * r + kKg * g + kKb * b)) / (2.0 * (1.0 - kKb));
}
double cr(double r, double g, double b) {
  return 128.0 + 224.0 / 255.0 * (r - (kKr * r + kKg * g + kKb * b)) / (2.0 * (1.0 - kKr));
}

// Chroma sample (i, j): [1 2 1] / 4 over columns 2i-1, 2i, 2i+1 (column 0 repeated at the
// left edge), averaged over rows 2j and 2j+1.
void reference_chroma(const Image& im, int i, int j, double& u, double& v) {
  double r = 0, g = 0, b = 0;
  const int cols[3] = {std::max(2 * i - 1, 0), 2 * i, 2 * i + 1};
  const double weights[3] = {0.125, 0.25, 0.125};
  for (int row = 2 * j; row <= 2 * j + 1; ++row) {
    for (int k = 0; k < 3; ++k) {
      const Rgba c = im.at(cols[k], row);
      r += weights[k] * c.r;
      g += weights[k] * c.g;
      b += weights[k] * c.b;
    }
  }
  u = cb(r, g, b);
  v = cr(r, g, b);
}

}  // namespace

TEST_CASE("yuv420: primaries, black, white and grey take their BT.709 limited-range codes") {
  struct Case {
    Rgba rgb;
    int y, u, v;
  };
  // Y' = 16 + 219 E'y, Cb = 128 + 224 (E'b - E'y) / 1.8556, Cr = 128 + 224 (E'r - E'y) / 1.5748.
  const Case cases[] = {
      {{0, 0, 0, 255}, 16, 128, 128},     {{255, 255, 255, 255}, 235, 128, 128},
      {{128, 128, 128, 255}, 126, 128, 128}, {{255, 0, 0, 255}, 63, 102, 240},
      {{0, 255, 0, 255}, 173, 42, 26},    {{0, 0, 255, 255}, 32, 240, 118},
  };
  for (const Case& c : cases) {
    const Planes p = convert(Image(6, 4, c.rgb));
    for (int yy = 0; yy < 4; ++yy)
      for (int x = 0; x < 6; ++x) CHECK(p.Y(x, yy) == c.y);
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 3; ++i) {
        CHECK(p.U(i, j) == c.u);
        CHECK(p.V(i, j) == c.v);
      }
    }
  }
}

TEST_CASE("yuv420: random images of random sizes match the definition to one code") {
  std::mt19937 rng(20261201);
  std::uniform_int_distribution<int> half_size(1, 40), byte(0, 255), kind(0, 2);
  long samples = 0, exact = 0;
  int worst = 0;
  for (int n = 0; n < 60; ++n) {
    const int w = 2 * half_size(rng), h = 2 * half_size(rng);
    Image im(w, h);
    // Noise, smooth ramps and flat patches: rounding meets every case.
    const int k = kind(rng);
    for (int yy = 0; yy < h; ++yy) {
      for (int x = 0; x < w; ++x) {
        Rgba c{static_cast<std::uint8_t>(byte(rng)), static_cast<std::uint8_t>(byte(rng)),
               static_cast<std::uint8_t>(byte(rng)), static_cast<std::uint8_t>(byte(rng))};
        if (k == 1) c = {static_cast<std::uint8_t>(255 * x / w), static_cast<std::uint8_t>(255 * yy / h), 90, 255};
        if (k == 2 && (x / 4 + yy / 4) % 2) c = {200, 40, 10, 255};
        im.set(x, yy, c);
      }
    }
    const Planes p = convert(im);
    auto tally = [&](int got, double want) {
      const int rounded = static_cast<int>(std::lround(want));
      const int off = std::abs(got - rounded);
      worst = std::max(worst, off);
      exact += off == 0;
      ++samples;
    };
    for (int yy = 0; yy < h; ++yy) {
      for (int x = 0; x < w; ++x) {
        const Rgba c = im.at(x, yy);
        tally(p.Y(x, yy), luma(c.r, c.g, c.b));
      }
    }
    for (int j = 0; j < h / 2; ++j) {
      for (int i = 0; i < w / 2; ++i) {
        double u = 0, v = 0;
        reference_chroma(im, i, j, u, v);
        tally(p.U(i, j), u);
        tally(p.V(i, j), v);
      }
    }
    // Padding past each row is left alone.
    CHECK(std::all_of(p.y.begin() + w, p.y.begin() + p.y_stride, [](std::uint8_t b) { return b == 0; }));
  }
  INFO(samples << " samples, " << exact << " exact");
  CHECK(worst <= 1);
  CHECK(static_cast<double>(exact) / static_cast<double>(samples) > 0.99);
}

TEST_CASE("yuv420: chroma is sited on the even columns, as H.264 players assume") {
  // One red column on grey. At an even column 2k it weighs 1/2 in chroma sample k and nothing
  // elsewhere; at an odd column 2k+1 it weighs 1/4 in samples k and k+1.
  const Rgba grey{100, 100, 100, 255}, red{250, 0, 0, 255};
  for (const int column : {6, 7}) {
    Image im(16, 2, grey);
    im.set(column, 0, red);
    im.set(column, 1, red);
    const Planes p = convert(im);
    for (int i = 0; i < 8; ++i) {
      double weight = 0.0;
      if (column % 2 == 0 && i == column / 2) weight = 0.5;
      if (column % 2 == 1 && (i == column / 2 || i == column / 2 + 1)) weight = 0.25;
      const double r = 100 + weight * 150, g = 100 - weight * 100, b = 100 - weight * 100;
      INFO("column " << column << ", chroma sample " << i);
      CHECK(std::abs(p.V(i, 0) - cr(r, g, b)) < 1.0);
      CHECK(std::abs(p.U(i, 0) - cb(r, g, b)) < 1.0);
    }
  }
}

TEST_CASE("yuv420: odd sizes are refused") {
  Planes p(8, 8);
  CHECK_THROWS_AS(rgba_to_yuv420_bt709(Image(7, 8), p.view()), ImageError);
  CHECK_THROWS_AS(rgba_to_yuv420_bt709(Image(8, 7), p.view()), ImageError);
}
