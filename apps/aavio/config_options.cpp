#include "config_options.hpp"

#include <CLI/CLI.hpp>

#include "aavio/io/presets.hpp"

namespace aavio::cli {

void AddConfigOptions(CLI::App& sub, config::ConfigSources* sources) {
  std::string names;
  for (const std::string& n : io::PresetNames())
    names += (names.empty() ? "" : ", ") + n;
  sub.add_option("--preset", sources->preset, "Parameter preset: " + names);
  std::string overlays;
  for (const std::string& n : io::OverlayNames())
    overlays += (overlays.empty() ? "" : ", ") + n;
  sub.add_option(
         "--config", sources->files,
         "YAML file(s) of parameters, or shipped overlays (" + overlays + "), applied in order")
      ->type_name("FILE");
  sub.add_option("--set", sources->overrides, "Override one parameter, e.g. --set mapping.eta=0.1")
      ->type_name("KEY=VALUE");
}

}  // namespace aavio::cli
