// The [overlay] keys of the forces-and-regimes layers (issue 22): several values, a title and
// a caption, contact force and velocity arrows, stick/slip/open badges. Read by
// read_render_settings (render_settings.cpp) through read_overlay_layers.
//
//   [overlay]
//   values = [{signal = "sphere.w", label = "spin", unit = "rad/s"}, ...]  # or [[overlay.values]]
//                            # shown below `signal` (which keeps working as the one-value form)
//   title = "..."            # default: the scene's `name`; "" turns it off
//   caption = "..."          # default: the scene's `description`; "" turns it off
//   forces = false           # normal (blue) and friction (orange) arrows at every contact point
//   force_scale = 0          # N per metre of arrow; 0: the largest force is 0.6 body sizes
//   velocities = false       # a velocity arrow per body (purple)
//   velocity_scale = 0       # (m/s) per metre of arrow; 0: the largest speed is 0.8 body sizes
//   badges = false           # "stick" / "slip" / "open" by each contact point and friction joint
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <string>
#include <vector>

namespace stiction::scene {
class TableReader;
}

namespace stiction::render {

struct OverlayValue {
  std::string signal;
  std::string label;  // default: the signal name
  std::string unit;
};

struct OverlayLayers {
  std::vector<OverlayValue> values;
  std::optional<std::string> title;    // unset: the scene's name
  std::optional<std::string> caption;  // unset: the scene's description
  bool forces = false;
  double force_scale = 0.0;  // N per metre; 0: automatic
  bool velocities = false;
  double velocity_scale = 0.0;  // (m/s) per metre; 0: automatic
  bool badges = false;
};

// Reads the keys above from the [overlay] table (before its finish()). `columns`: the
// trajectory columns a value's signal must match (empty: not checked).
void read_overlay_layers(scene::TableReader& overlay, OverlayLayers& layers,
                         const std::vector<std::string>& columns);

// Fills an unset title and caption from the document's top-level `name` and `description`.
void default_title_and_caption(const toml::table& document, OverlayLayers& layers);

}  // namespace stiction::render
