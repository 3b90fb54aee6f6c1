#include "config_options.hpp"

#include <CLI/CLI.hpp>

#include "aavio/common/config_fields.hpp"
#include "aavio/config/presets.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "cli.hpp"

namespace aavio::cli {

void AddConfigOptions(CLI::App& sub, config::ConfigSources* sources) {
  std::string names;
  for (const std::string& n : config::PresetNames())
    names += (names.empty() ? "" : ", ") + n;
  sub.add_option("--preset", sources->preset, "Parameter preset: " + names);
  std::string overlays;
  for (const std::string& n : config::OverlayNames())
    overlays += (overlays.empty() ? "" : ", ") + n;
  sub.add_option(
         "--config", sources->files,
         "YAML file(s) of parameters, or shipped overlays (" + overlays + "), applied in order")
      ->type_name("FILE");
  // A key that does not exist or a value that cannot be one (NaN, text for a number) is a wrong
  // argument, refused while parsing; ranges are checked once every source is applied.
  sub.add_option("--set", sources->overrides, "Override one parameter, e.g. --set mapping.eta=0.1")
      ->type_name("KEY=VALUE")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            Expected<ConfigEntry> entry = ParseKeyValueOverride(text);
            if (!entry) return entry.status().message();
            pipeline::OdometryConfig probe;
            const Status applied = ApplyConfigEntries({*entry}, &probe);
            return applied.ok() ? std::string() : applied.message();
          },
          "", ""));
}

int ConfigErrorExitCode(const config::ConfigSources& sources) {
  if (sources.overrides.empty()) return kExitError;
  config::ConfigSources without = sources;
  without.overrides.clear();
  return config::ResolveOdometryConfig(without).ok() ? kExitUsage : kExitError;
}

}  // namespace aavio::cli
