#include "image/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "image/png.hpp"

namespace stiction::image {
namespace {

int channel_difference(const std::uint8_t* a, const std::uint8_t* b) {
  int d = 0;
  for (int i = 0; i < 4; ++i) d = std::max(d, std::abs(int(a[i]) - int(b[i])));
  return d;
}

bool update_requested() {
  const char* v = std::getenv("STICTION_UPDATE_GOLDEN");
  return v && *v && std::strcmp(v, "0") != 0;
}

}  // namespace

CompareResult compare_images(const Image& expected, const Image& actual,
                             const CompareOptions& options) {
  CompareResult r;
  std::ostringstream msg;
  if (expected.width != actual.width || expected.height != actual.height) {
    r.size_mismatch = true;
    msg << "size differs: expected " << expected.width << "x" << expected.height << ", actual "
        << actual.width << "x" << actual.height;
    r.message = msg.str();
    return r;
  }
  const long count = static_cast<long>(expected.width) * expected.height;
  double squares = 0.0;
  for (long i = 0; i < count; ++i) {
    const std::uint8_t* e = &expected.pixels[i * 4];
    const std::uint8_t* a = &actual.pixels[i * 4];
    const int d = channel_difference(e, a);
    r.max_channel_difference = std::max(r.max_channel_difference, d);
    if (d > options.channel_tolerance) ++r.pixels_off;
    for (int c = 0; c < 3; ++c) squares += double(int(e[c]) - int(a[c])) * double(int(e[c]) - int(a[c]));
  }
  r.fraction_off = count > 0 ? double(r.pixels_off) / double(count) : 0.0;
  r.rms = count > 0 ? std::sqrt(squares / (3.0 * double(count))) : 0.0;
  r.matches = r.fraction_off <= options.max_fraction && r.rms <= options.max_rms;
  msg << r.pixels_off << " of " << count << " pixels (" << r.fraction_off * 100.0
      << "%) off by more than " << options.channel_tolerance << "/255 (allowed "
      << options.max_fraction * 100.0 << "%), largest channel difference "
      << r.max_channel_difference << ", RMS " << r.rms;
  if (options.max_rms < 255.0) msg << " (allowed " << options.max_rms << ")";
  r.message = msg.str();
  return r;
}

Image diff_image(const Image& expected, const Image& actual, int channel_tolerance) {
  const int w = std::min(expected.width, actual.width);
  const int h = std::min(expected.height, actual.height);
  Image out(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::uint8_t* e = expected.data(x, y);
      const int d = channel_difference(e, actual.data(x, y));
      const auto grey = static_cast<std::uint8_t>((e[0] * 77 + e[1] * 150 + e[2] * 29) >> 10);
      if (d > channel_tolerance) {
        out.set(x, y, {static_cast<std::uint8_t>(std::min(255, 128 + d)), 0, 0, 255});
      } else if (d > 0) {
        out.set(x, y, {200, 200, 0, 255});
      } else {
        out.set(x, y, {grey, grey, grey, 255});
      }
    }
  }
  return out;
}

CompareResult compare_to_golden(const std::filesystem::path& golden, const Image& actual,
                                const std::filesystem::path& failure_dir,
                                const CompareOptions& options) {
  if (update_requested()) {
    if (golden.has_parent_path()) std::filesystem::create_directories(golden.parent_path());
    write_png(golden, actual, PngSpeed::small);
    CompareResult r;
    r.matches = true;
    r.message = "golden updated: " + golden.string();
    return r;
  }
  const std::string stem = golden.stem().string();
  std::filesystem::create_directories(failure_dir);
  const auto actual_path = failure_dir / (stem + ".actual.png");
  if (!std::filesystem::exists(golden)) {
    write_png(actual_path, actual, PngSpeed::small);
    CompareResult r;
    r.message = "golden " + golden.string() + " is missing; actual image written to " +
                actual_path.string() + " (run with STICTION_UPDATE_GOLDEN=1 to create it)";
    return r;
  }
  const Image expected = read_png(golden);
  CompareResult r = compare_images(expected, actual, options);
  if (!r.matches) {
    const auto expected_path = failure_dir / (stem + ".expected.png");
    const auto diff_path = failure_dir / (stem + ".diff.png");
    write_png(expected_path, expected, PngSpeed::small);
    write_png(actual_path, actual, PngSpeed::small);
    write_png(diff_path, diff_image(expected, actual, options.channel_tolerance), PngSpeed::small);
    r.message = golden.string() + ": " + r.message + "; see " + expected_path.string() + ", " +
                actual_path.string() + ", " + diff_path.string() +
                " (STICTION_UPDATE_GOLDEN=1 regenerates the golden after an intended change)";
  } else {
    r.message = golden.string() + ": " + r.message;
  }
  return r;
}

}  // namespace stiction::image
