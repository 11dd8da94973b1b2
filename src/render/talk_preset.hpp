// [render] preset = "talk": one key for a video to show in a talk (issue 37 item 6). It sets
//   size = [1280, 720]                  a 16:9 frame
//   slow_motion_around_events = 0.1     8x slower (event_slow_motion) within 0.1 s of ...
//   slowed_events = 3                   ... the first three episodes of slip/stick changes
//   [overlay] badges, forces and trail = true
//   [inset] signals: the ones that matter for the scene (talk_inset_signals)
// Every key given in the scene file wins over the preset's value: the preset is applied
// first, then the tables are read over it.
//
// Why `preset` and not a new key: the issue and DESIGN name `[render] preset = "talk"`, and
// `preset` was libx264's speed preset. Both stay: a look name ("talk") selects a look, an
// x264 name ("ultrafast", ...) keeps meaning the encoder's speed, as older scene files use
// it; the encoder's speed has its own key now, `encoder_preset`, so a talk video can choose
// it too. The two sets of names do not overlap.
#pragma once

#include <string>
#include <vector>

#include "render/render_settings.hpp"

namespace stiction::render {

// The look presets: "talk".
const std::vector<std::string>& look_preset_names();
bool is_look_preset(const std::string& name);

// The inset's signals for a talk, from the trajectory's columns: the slip speed of the first
// contact or friction element with one ("slip speed", m/s), then the speed of the first body
// with a velocity ("speed", m/s), or for a scene without those the first joint's rate
// ("joint speed", rad/s). Fills signals, labels and units; none found: no inset.
InsetSettings talk_inset(const std::vector<std::string>& columns);

// Sets the talk preset's values in `settings` (before the scene's tables are read over it).
void apply_talk_preset(RenderSettings& settings, const std::vector<std::string>& columns);

}  // namespace stiction::render
