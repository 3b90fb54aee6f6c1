#pragma once
/// Builds the effective OdometryConfig from its sources, in this order (later wins):
/// defaults → the sensor's settings (when the rig is known; pipeline/sensor_settings.hpp) →
/// a preset (configs/*.yaml, embedded) → YAML files (each, in order; a shipped overlay's name
/// unless a file of that name exists) → overlays (`run --esvo`) → key=value overrides. The CLI's
/// --preset, --config and --set fill these; a program does the same:
///
///   config::ConfigSources sources;                // sources.preset = "indoor" to choose
///   config::ConfigureForRig(rig, &sources);       // the sensor's settings, a suggested preset
///   Expected<pipeline::OdometryConfig> c = config::ResolveOdometryConfig(sources);

#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/pipeline/scene_depth_probe.hpp"
#include "aavio/pipeline/sensor_settings.hpp"

namespace aavio::config {

struct ConfigSources {
  std::string preset;
  std::vector<std::string> files;
  std::vector<std::string> overlays;  ///< shipped overlays by name, always the embedded ones
  std::vector<std::string> overrides;
  std::optional<pipeline::SensorFacts> sensor;  ///< the rig the configuration is for, if known
};

/// Makes `sources` configure for `rig`: its sensor's settings and, when no preset is named, the
/// preset the rig suggests — by its baseline; a car's baseline is indoor when the scene's
/// measured depths (`scene`, from pipeline::SceneDepthProbe) fall within the indoor preset's
/// depth range more than within the driving preset's. Returns why that preset ("" when one was
/// named).
std::string ConfigureForRig(const geometry::StereoRig& rig, ConfigSources* sources,
                            const std::optional<pipeline::SceneDepth>& scene = {});

/// The settings derived from `sources.sensor` (none without one), for the scene the other
/// sources make.
Expected<std::vector<pipeline::SensorSetting>> SensorSettingsOf(const ConfigSources& sources);

/// Applies the sources and validates the result.
Expected<pipeline::OdometryConfig> ResolveOdometryConfig(const ConfigSources& sources);

/// A description of the sources for the header of a written config ("preset driving + my.yaml",
/// after the sensor's settings when there are any).
std::string DescribeSources(const ConfigSources& sources);

}  // namespace aavio::config
