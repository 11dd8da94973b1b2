#include "services/verify_settings.hpp"

#include <cmath>
#include <cstdio>

#include "scene/toml_reader.hpp"

namespace stiction::services {

VerifySettings read_verify_settings(const toml::table& document, double duration) {
  VerifySettings s;
  scene::TableReader root(document, "");
  if (!root.has("verify")) return s;
  if (!document.get("verify")->is_table()) root.fail("verify", "expected a table");
  scene::TableReader r = *root.subtable("verify");
  if (r.has("at")) {
    s.at = r.numbers("at");
    for (double t : s.at) {
      if (!(t >= 0.0 && t <= duration)) {
        char range[64];
        std::snprintf(range, sizeof range, "%g", duration);
        r.fail("at", std::string("frame times must lie in the run, 0..") + range + " s");
      }
    }
  }
  s.frames = r.boolean("frames", s.frames);
  s.figures = r.boolean("figures", s.figures);
  const long tolerance = r.integer("pixel_tolerance", s.pixel_tolerance);
  if (tolerance < 0 || tolerance > 255) r.fail("pixel_tolerance", "must be in 0..255");
  s.pixel_tolerance = static_cast<int>(tolerance);
  s.max_differing = r.non_negative("max_differing", s.max_differing);
  if (s.max_differing > 1.0) r.fail("max_differing", "is a share of the pixels: must be in 0..1");
  s.max_rms = r.non_negative("max_rms", s.max_rms);
  if (s.max_rms > 255.0) r.fail("max_rms", "must be in 0..255");
  s.rel_tolerance = r.non_negative("rel_tolerance", s.rel_tolerance);
  s.abs_tolerance = r.non_negative("abs_tolerance", s.abs_tolerance);
  r.finish();
  return s;
}

}  // namespace stiction::services
