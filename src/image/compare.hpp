// Golden-image comparison with a tolerance: a pixel is "off" when any channel differs by
// more than channel_tolerance/255; the images match when at most max_fraction of the pixels
// are off and the RMS channel difference (over R, G, B of every pixel, in 0..255) is at most
// max_rms. On failure, NAME.expected.png, NAME.actual.png and NAME.diff.png are written to a
// failure directory for inspection.
//
// Regenerating goldens after an intended change: run the tests with the environment variable
// STICTION_UPDATE_GOLDEN=1; compare_to_golden then (over)writes the golden file and passes.
#pragma once

#include <filesystem>
#include <string>

#include "image/image.hpp"

namespace stiction::image {

struct CompareOptions {
  int channel_tolerance = 5;    // out of 255
  double max_fraction = 0.001;  // 0.1% of the pixels
  double max_rms = 255.0;       // RMS channel difference allowed (255: no limit)
};

struct CompareResult {
  bool matches = false;
  bool size_mismatch = false;
  long pixels_off = 0;
  double fraction_off = 0.0;
  int max_channel_difference = 0;
  double rms = 0.0;  // RMS of the R, G, B differences over all pixels, 0..255
  std::string message;  // one line, for test output
};

CompareResult compare_images(const Image& expected, const Image& actual,
                             const CompareOptions& options = {});

// A visual diff: the expected image greyed and dimmed, pixels off drawn in red (brightness
// by the size of the difference), pixels that differ within tolerance in yellow.
Image diff_image(const Image& expected, const Image& actual, int channel_tolerance);

// Compares `actual` with the PNG at `golden`. A missing golden is a failure (the actual image
// is still written). On failure writes STEM.expected.png / STEM.actual.png / STEM.diff.png
// (STEM = the golden's file stem) into `failure_dir` and names them in the message.
// With STICTION_UPDATE_GOLDEN=1 in the environment, writes `actual` as the golden and passes.
CompareResult compare_to_golden(const std::filesystem::path& golden, const Image& actual,
                                const std::filesystem::path& failure_dir,
                                const CompareOptions& options = {});

}  // namespace stiction::image
