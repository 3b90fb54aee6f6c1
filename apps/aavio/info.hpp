#pragma once
// Internal to `aavio info`: the data half (info_data.cpp) of the command in info_command.cpp.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "aavio/common/status.hpp"

namespace aavio::cli {

/// True for event files (.h5, .bag, .txt, .raw), sequence.yaml and folders holding a sequence.
bool LooksLikeData(const std::string& path);
/// Fills `json` and a human-readable `text` describing the data at `path`; with `stats`, each
/// event stream's sensor statistics too (events/event_statistics.hpp).
Status DescribeData(const std::string& path, bool stats, nlohmann::json* json, std::string* text);

}  // namespace aavio::cli
