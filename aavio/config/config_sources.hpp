#pragma once
/// Builds the effective OdometryConfig from its sources: on the defaults, a preset
/// (configs/*.yaml, embedded) → YAML files (each, in order; a shipped overlay's name unless a
/// file of that name exists) → overlays (`run --esvo`) → key=value overrides, later winning;
/// then, once, the sensor's rules (when the rig is known; sensor_rules.hpp) on every field none
/// of those set. The CLI's --preset, --config and --set fill these; a program does the same:
///
///   config::ConfigSources sources;                // sources.preset = "indoor" to choose
///   config::ConfigureForRig(rig, &sources);       // the sensor's settings, a suggested preset
///   Expected<pipeline::OdometryConfig> c = config::ResolveOdometryConfig(sources);

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/config/sensor_rules.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/pipeline/scene_depth_probe.hpp"

namespace aavio::config {

struct ConfigSources {
  std::string preset;
  std::vector<std::string> files;
  std::vector<std::string> overlays;  ///< shipped overlays by name, always the embedded ones
  std::vector<std::string> overrides;
  std::optional<SensorFacts> sensor;  ///< the rig the configuration is for, if known
  /// What the scene's measured depths set (ConfigureForRig), applied after the preset: files,
  /// overlays and overrides still win.
  std::vector<ConfigEntry> scene;
};

/// Makes `sources` configure for `rig`: its sensor's settings and, when no preset is named, the
/// preset the rig suggests — by its baseline; a car's baseline is indoor when the scene's
/// measured depths (`scene`, from pipeline::SceneDepthProbe) fall within the indoor preset's
/// depth range more than within the driving preset's. A smaller rig keeps the indoor preset,
/// but when most of the scene lies beyond its depth range (a hand-held camera in a street),
/// the range reaches twice the scene's 90th-percentile depth, as far as half a pixel of
/// disparity (`sources->scene`). Returns why that preset ("" when one was named).
std::string ConfigureForRig(const geometry::StereoRig& rig, ConfigSources* sources,
                            const std::optional<pipeline::SceneDepth>& scene = {});

/// The configuration and where each value came from.
struct ResolvedConfig {
  pipeline::OdometryConfig config;
  /// Key → its value's origin ("preset indoor:12", "my.yaml:3", "--set", "the sensor's rule
  /// (...)"); a key not listed has its default.
  std::map<std::string, std::string> origin;
  /// Every sensor rule's value, also those a source overrode (SensorRuling::applied).
  std::vector<SensorRuling> sensor_rulings;
};

/// Applies the sources, then the sensor's rules, and validates the result.
Expected<ResolvedConfig> Resolve(const ConfigSources& sources);
/// Resolve's configuration alone.
Expected<pipeline::OdometryConfig> ResolveOdometryConfig(const ConfigSources& sources);

/// A description of the sources for the header of a written config ("preset driving + my.yaml",
/// after the sensor's settings when there are any).
std::string DescribeSources(const ConfigSources& sources);

}  // namespace aavio::config
