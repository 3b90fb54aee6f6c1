#include "aavio/config/presets.hpp"

#include "aavio/io/config_yaml.hpp"

namespace aavio::config {
namespace {

std::vector<std::string> Names(bool overlay) {
  std::vector<std::string> names;
  for (const EmbeddedPreset& preset : EmbeddedPresets()) {
    if (preset.overlay == overlay) names.emplace_back(preset.name);
  }
  return names;
}

Expected<std::vector<ConfigEntry>> Entries(const std::string& name, bool overlay) {
  const char* kind = overlay ? "overlay" : "preset";
  for (const EmbeddedPreset& preset : EmbeddedPresets()) {
    if (preset.overlay == overlay && name == preset.name)
      return io::ParseConfigYaml(preset.yaml, std::string(kind) + " " + name);
  }
  std::string known;
  for (const std::string& n : Names(overlay))
    known += (known.empty() ? "" : ", ") + n;
  std::string hint;
  if (!overlay && (name == "rpg" || name == "dsec")) {
    hint =
        " (presets are scene kinds now: rpg became indoor, dsec driving; the camera's "
        "settings come from its calibration)";
  }
  return NotFound("no " + std::string(kind) + " named '" + name + "'; " + kind + "s: " + known +
                  hint);
}

}  // namespace

std::vector<std::string> PresetNames() {
  return Names(false);
}

std::vector<std::string> OverlayNames() {
  return Names(true);
}

Expected<std::vector<ConfigEntry>> PresetEntries(const std::string& name) {
  return Entries(name, false);
}

Expected<std::vector<ConfigEntry>> OverlayEntries(const std::string& name) {
  return Entries(name, true);
}

}  // namespace aavio::config
