#include "render/overlay_layers_settings.hpp"

#include <algorithm>

#include "render/scene_view.hpp"
#include "scene/toml_reader.hpp"

namespace stiction::render {
namespace {

bool known_signal(const std::string& signal, const std::vector<std::string>& columns) {
  return columns.empty() || std::any_of(columns.begin(), columns.end(), [&](const std::string& c) {
           return c == signal || is_axis_of(c, signal);
         });
}

double scale(scene::TableReader& r, const char* key) {
  const double v = r.number(key, 0.0);
  if (!(v >= 0.0)) r.fail(key, "must be >= 0 (0: chosen from the run's largest value)");
  return v;
}

}  // namespace

void read_overlay_layers(scene::TableReader& r, OverlayLayers& layers,
                         const std::vector<std::string>& columns) {
  for (scene::TableReader& v : r.array_of_tables("values")) {
    OverlayValue value;
    value.signal = v.required_string("signal");
    if (!known_signal(value.signal, columns)) {
      v.fail("signal", "no signal named '" + value.signal + "'");
    }
    value.label = v.string("label", value.signal);
    value.unit = v.string("unit", "");
    v.finish();
    layers.values.push_back(std::move(value));
  }
  if (r.has("title")) layers.title = r.string("title", "");
  if (r.has("caption")) layers.caption = r.string("caption", "");
  layers.forces = r.boolean("forces", layers.forces);
  layers.force_scale = scale(r, "force_scale");
  layers.velocities = r.boolean("velocities", layers.velocities);
  layers.velocity_scale = scale(r, "velocity_scale");
  layers.badges = r.boolean("badges", layers.badges);
}

void default_title_and_caption(const toml::table& document, OverlayLayers& layers) {
  if (!layers.title) layers.title = document["name"].value<std::string>().value_or("");
  if (!layers.caption) layers.caption = document["description"].value<std::string>().value_or("");
}

}  // namespace stiction::render
