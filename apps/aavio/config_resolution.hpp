#pragma once
/// Builds the effective OdometryConfig from its sources, in this order (later wins):
/// defaults → --preset NAME → --config FILE (each, in order; a shipped overlay's name unless a
/// file of that name exists) → overlays a command adds (`run --esvo`) → --set key=value.

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/pipeline/odometry_config.hpp"

namespace CLI {
class App;
}

namespace aavio::cli {

struct ConfigSources {
  std::string preset;
  std::vector<std::string> files;
  std::vector<std::string> overlays;  ///< shipped overlays by name, always the embedded ones
  std::vector<std::string> overrides;
};

/// Adds --preset, --config and --set to a subcommand.
void AddConfigOptions(CLI::App& sub, ConfigSources* sources);

/// Applies the sources and validates the result.
Expected<pipeline::OdometryConfig> ResolveOdometryConfig(const ConfigSources& sources);

/// A description of the sources for the header of a written config ("preset dsec + my.yaml").
std::string DescribeSources(const ConfigSources& sources);

}  // namespace aavio::cli
