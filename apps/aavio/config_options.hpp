#pragma once
/// The configuration options every command that runs the odometry takes.

#include "aavio/config/config_sources.hpp"

namespace CLI {
class App;
}

namespace aavio::cli {

/// Adds --preset, --config and --set to a subcommand.
void AddConfigOptions(CLI::App& sub, config::ConfigSources* sources);

}  // namespace aavio::cli
