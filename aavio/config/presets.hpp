#pragma once
/// Configuration presets and overlays by name. Their text is configs/<name>.yaml and
/// configs/overlays/<name>.yaml, embedded at build time: a preset is a whole configuration
/// (`--preset`), an overlay a few keys applied on top of one (`--config NAME`).

#include <string>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/common/status.hpp"

namespace aavio::config {

struct EmbeddedPreset {
  const char* name;
  const char* yaml;
  bool overlay;
};

/// Every preset compiled into this binary (generated source).
const std::vector<EmbeddedPreset>& EmbeddedPresets();

std::vector<std::string> PresetNames();
std::vector<std::string> OverlayNames();

/// The entries of preset `name`; NotFound listing the presets that exist.
Expected<std::vector<ConfigEntry>> PresetEntries(const std::string& name);
/// The entries of overlay `name`; NotFound listing the overlays that exist.
Expected<std::vector<ConfigEntry>> OverlayEntries(const std::string& name);

}  // namespace aavio::config
