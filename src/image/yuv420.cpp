#include "image/yuv420.hpp"

#include <cstring>
#include <string>
#include <vector>

namespace stiction::image {
namespace {

// 16-bit fixed point. The loops below are written so that GCC vectorizes them at -O3:
// pixels are read as 32-bit words and split with shifts (RGBA is little-endian R first),
// and the chroma filter reads column sums from plain int arrays.
constexpr int kShift = 16;
constexpr int fixed(double v) { return static_cast<int>(v * (1 << kShift) + (v < 0 ? -0.5 : 0.5)); }

constexpr double kKr = 0.2126, kKb = 0.0722, kKg = 1.0 - kKr - kKb;  // BT.709
constexpr double kLuma = 219.0 / 255.0, kChroma = 224.0 / 255.0;     // limited range
constexpr int kYr = fixed(kLuma * kKr), kYg = fixed(kLuma * kKg), kYb = fixed(kLuma * kKb);
// Cb = (B' - Y') / (2 (1 - Kb)), Cr = (R' - Y') / (2 (1 - Kr)). The green coefficient takes
// the rounding so that each row sums to exactly zero: greys give 128 exactly.
constexpr int kUr = fixed(-kChroma * kKr / (2 * (1 - kKb))), kUb = fixed(kChroma * 0.5);
constexpr int kUg = -(kUr + kUb);
constexpr int kVr = fixed(kChroma * 0.5), kVb = fixed(-kChroma * kKb / (2 * (1 - kKr)));
constexpr int kVg = -(kVr + kVb);

inline std::uint32_t word(const std::uint8_t* p) {
  std::uint32_t w;
  std::memcpy(&w, p, 4);
  return w;
}

}  // namespace

// On x86-64 an AVX2 copy is built beside the baseline one and picked at load time (GCC's
// function multi-versioning): twice as many pixels per instruction where the CPU has it.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void rgba_to_yuv420_bt709(const Image& rgba, const Yuv420Planes& out) {
  const int w = rgba.width, h = rgba.height;
  if (w <= 0 || h <= 0 || w % 2 || h % 2) {
    throw ImageError("yuv420 needs an even, non-empty size, got " + std::to_string(w) + "x" +
                     std::to_string(h));
  }
  const std::size_t stride = rgba.stride();

  constexpr int kLumaOffset = (16 << kShift) + (1 << (kShift - 1));
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* row = rgba.pixels.data() + static_cast<std::size_t>(y) * stride;
    std::uint8_t* __restrict luma = out.y + static_cast<std::ptrdiff_t>(y) * out.y_stride;
    for (int x = 0; x < w; ++x) {
      const std::uint32_t p = word(row + 4 * x);
      const int r = p & 0xff, g = (p >> 8) & 0xff, b = (p >> 16) & 0xff;
      luma[x] = static_cast<std::uint8_t>((kYr * r + kYg * g + kYb * b + kLumaOffset) >> kShift);
    }
  }

  // Per row pair: the sum of each column over the two rows, per channel; then the [1 2 1]
  // filter around each even column. The weights sum to 8, hence the 3 more bits of shift.
  std::vector<int> sums(3 * static_cast<std::size_t>(w));
  int* __restrict sr = sums.data();
  int* __restrict sg = sr + w;
  int* __restrict sb = sg + w;
  constexpr int kChromaShift = kShift + 3;
  constexpr int kChromaOffset = (128 << kChromaShift) + (1 << (kChromaShift - 1));
  for (int j = 0; j < h / 2; ++j) {
    const std::uint8_t* top = rgba.pixels.data() + static_cast<std::size_t>(2 * j) * stride;
    const std::uint8_t* bottom = top + stride;
    for (int x = 0; x < w; ++x) {
      const std::uint32_t a = word(top + 4 * x), b = word(bottom + 4 * x);
      sr[x] = static_cast<int>((a & 0xff) + (b & 0xff));
      sg[x] = static_cast<int>(((a >> 8) & 0xff) + ((b >> 8) & 0xff));
      sb[x] = static_cast<int>(((a >> 16) & 0xff) + ((b >> 16) & 0xff));
    }
    std::uint8_t* __restrict cb = out.u + static_cast<std::ptrdiff_t>(j) * out.u_stride;
    std::uint8_t* __restrict cr = out.v + static_cast<std::ptrdiff_t>(j) * out.v_stride;
    const auto chroma = [&](int i, int left) {
      const int x = 2 * i;
      const int r = sr[left] + 2 * sr[x] + sr[x + 1];
      const int g = sg[left] + 2 * sg[x] + sg[x + 1];
      const int b = sb[left] + 2 * sb[x] + sb[x + 1];
      cb[i] = static_cast<std::uint8_t>((kUr * r + kUg * g + kUb * b + kChromaOffset) >> kChromaShift);
      cr[i] = static_cast<std::uint8_t>((kVr * r + kVg * g + kVb * b + kChromaOffset) >> kChromaShift);
    };
    chroma(0, 0);  // the left edge repeats column 0
    for (int i = 1; i < w / 2; ++i) chroma(i, 2 * i - 1);
  }
}

}  // namespace stiction::image
