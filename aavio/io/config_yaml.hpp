#pragma once
/// The only configuration parser: YAML files whose sections mirror the config structs
/// (`mapping: {static_stereo: {zncc_threshold: 0.2}}` sets `mapping.static_stereo.zncc_threshold`).
/// Entries are applied with ApplyConfigEntries (common/config_fields.hpp), which rejects unknown
/// keys with a did-you-mean hint.

#include <string>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/common/status.hpp"

namespace aavio::io {

/// Flattens YAML text into dotted entries; each value's origin is "origin:line".
Expected<std::vector<ConfigEntry>> ParseConfigYaml(const std::string& text,
                                                   const std::string& origin);
Expected<std::vector<ConfigEntry>> ReadConfigYaml(const std::string& path);

/// Nested YAML for the entries (in their order; consecutive keys of a section are grouped),
/// each line of `header` written as a leading comment.
std::string FormatConfigYaml(const std::vector<ConfigEntry>& entries, const std::string& header);

/// Writes `text` to `path` (truncating). IoError naming the path on failure.
Status WriteTextFile(const std::string& path, const std::string& text);

}  // namespace aavio::io
