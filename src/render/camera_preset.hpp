// The [camera] `view` key: named camera presets. "auto" is the automatic framing (a
// three-quarter view from the front, or facing an arm's plane; `follow` as documented), "side"
// looks horizontally at the mechanism's front, "top" straight down, "three_quarter" from a
// front corner, higher and more from the side than "auto", and "follow" tracks the `follow`
// body (or the first body) horizontally at a fixed height. Every fixed preset frames every
// element of the mechanism over the whole run.
#pragma once

#include <string>
#include <vector>

namespace stiction::scene {
class TableReader;
}

namespace stiction::render {

enum class CameraView { automatic, side, top, three_quarter, follow };

// The names as written in the scene file, in the order of CameraView.
const std::vector<std::string>& camera_view_names();

// Reads `view` from the [camera] table (default "auto"); an unknown name is an InputError at
// the key, listing the names.
CameraView read_camera_view(scene::TableReader& camera);

}  // namespace stiction::render
