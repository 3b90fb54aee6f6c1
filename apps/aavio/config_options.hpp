#pragma once
/// The configuration options every command that runs the odometry takes.

#include "aavio/config/config_sources.hpp"

namespace CLI {
class App;
}

namespace aavio::cli {

/// Adds --preset, --config and --set to a subcommand.
void AddConfigOptions(CLI::App& sub, config::ConfigSources* sources);

/// The exit code of a configuration that failed to resolve: kExitUsage when the --set overrides
/// are the cause (the rest resolves without them), a number out of range given as an argument;
/// else kExitError (a file or preset).
int ConfigErrorExitCode(const config::ConfigSources& sources);

}  // namespace aavio::cli
