// The scene file's [verify] table: what `stiction verify` compares and how strictly. Every
// key is optional; a bad value or an unknown key is a scene::InputError
// "FILE:LINE:COL: error: verify.KEY: ..." (exit code 2), for `run`, `check` and `verify` alike.
//
//   [verify]
//   at = [0.0, 0.5, 2.0]     # frame times in s (default: first frame, each event, last frame)
//   frames = true            # compare rendered frames
//   figures = true           # compare the scene's figures (plots/*.png)
//   pixel_tolerance = 16     # a pixel differs when a channel differs by more (0..255)
//   max_differing = 0.002    # share of differing pixels that still matches (0..1)
//   max_rms = 4.0            # RMS channel difference over the image that still matches (0..255)
//   rel_tolerance = 1e-6     # numbers match when |a - g| <= abs + rel * |g|
//   abs_tolerance = 1e-9
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

namespace stiction::services {

struct VerifySettings {
  std::vector<double> at;  // empty: first frame, each event, last frame
  bool frames = true;
  bool figures = true;
  int pixel_tolerance = 16;
  double max_differing = 0.002;
  double max_rms = 4.0;
  double rel_tolerance = 1e-6;
  double abs_tolerance = 1e-9;
};

// Reads [verify] of `document` (absent: the defaults). `duration` bounds the frame times.
VerifySettings read_verify_settings(const toml::table& document, double duration);

}  // namespace stiction::services
