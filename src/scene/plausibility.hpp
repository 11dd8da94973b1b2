// Load-time plausibility checks: values that are valid but most likely a unit or sign mistake
// (gravity pointing away from the contacts, mu = 20, an angle in degrees, a 7 kg ball of
// radius 10.9 m, `settle` on a body far above its surface, a step longer than the run, ...).
// They are warnings, not errors: the scene still runs. Each check is cheap (no simulation)
// and its bound is documented in docs/scene_format.md ("Plausibility warnings"); none fires
// on a bundled scene (tests/scene/test_plausibility.cpp).
#pragma once

#include <string>
#include <vector>

namespace stiction::scene {

struct Scene;

// One warning, located as errors are (FILE:LINE:COL) and naming the dotted key it is about.
struct Warning {
  std::string file;
  long line = 0;
  long column = 0;
  std::string key;   // e.g. "impedances.floor.mu"
  std::string text;  // starts with the key
};

// Every plausibility warning of a built scene (network finalized), in file order.
std::vector<Warning> plausibility_warnings(const Scene& scene);

// "FILE:LINE:COL: warning: TEXT", as printed on stderr.
std::string format_warning(const Warning& warning);

}  // namespace stiction::scene
