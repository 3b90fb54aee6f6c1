#pragma once
/// Configuration presets by name. Their text is configs/<name>.yaml, embedded at build time.

#include <string>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/common/status.hpp"

namespace aavio::io {

struct EmbeddedPreset {
  const char* name;
  const char* yaml;
};

/// Every preset compiled into this binary (generated source).
const std::vector<EmbeddedPreset>& EmbeddedPresets();

std::vector<std::string> PresetNames();

/// The entries of preset `name`; NotFound listing the presets that exist.
Expected<std::vector<ConfigEntry>> PresetEntries(const std::string& name);

}  // namespace aavio::io
