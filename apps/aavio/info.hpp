#pragma once
// Internal to `aavio info`: the data half (info_data.cpp) of the command in info_command.cpp.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "aavio/common/status.hpp"

namespace aavio::cli {

/// True for event files (.h5, .bag, .txt), sequence.yaml and folders holding a sequence.
bool LooksLikeData(const std::string& path);
/// Fills `json` and a human-readable `text` describing the data at `path`.
Status DescribeData(const std::string& path, nlohmann::json* json, std::string* text);

}  // namespace aavio::cli
