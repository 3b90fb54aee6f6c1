#include "aavio/io/presets.hpp"

#include "aavio/io/config_yaml.hpp"

namespace aavio::io {

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const EmbeddedPreset& preset : EmbeddedPresets())
    names.emplace_back(preset.name);
  return names;
}

Expected<std::vector<ConfigEntry>> PresetEntries(const std::string& name) {
  for (const EmbeddedPreset& preset : EmbeddedPresets()) {
    if (name == preset.name) return ParseConfigYaml(preset.yaml, "preset " + name);
  }
  std::string known;
  for (const std::string& n : PresetNames())
    known += (known.empty() ? "" : ", ") + n;
  return NotFound("no preset named '" + name + "'; presets: " + known);
}

}  // namespace aavio::io
