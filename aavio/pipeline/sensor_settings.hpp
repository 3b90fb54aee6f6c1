#pragma once
/// The settings that follow from the sensor, not from the scene: what a user with a new stereo
/// rig would otherwise have to choose per dataset. Each comes with the rule that gave it, which
/// `aavio config --for SEQUENCE` prints. The rules reproduce the reference values on the rigs
/// they were chosen for (rpg's DAVIS240C pair, DSEC's 640×480 pair) and extend them to others.
///
/// What genuinely differs between scenes (depth range, motion kind: fusion, temporal stereo's
/// baseline, the tracking's motion model) is a preset's (configs/indoor.yaml,
/// configs/driving.yaml); `SuggestPreset` picks one from the rig when none is named.
///
/// The resolution: defaults → sensor settings (this file) → preset → files → --set, where a
/// sensor setting that depends on the scene (the σ_ρ/ρ culling, on the depth range) is computed
/// from the configuration the later sources make (apps/aavio/config_resolution.cpp).

#include <string>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::pipeline {

/// What the settings depend on: the rectified stereo rig.
struct SensorFacts {
  int width_px = 0;
  int height_px = 0;
  double focal_px = 0.0;    ///< rectified focal length f
  double baseline_m = 0.0;  ///< b

  static SensorFacts Of(const geometry::StereoRig& rig);
  /// "1280 x 720 px, f 974.8 px, baseline 0.1185 m (f*b 115.5 px*m)"
  std::string Describe() const;
};

/// One derived value, as the text a config file would hold, and why.
struct SensorSetting {
  std::string key;
  std::string value;
  std::string rule;
};

/// The sensor's settings. `scene` supplies what a rule also needs from the scene (the depth
/// range); nothing else of it is read.
std::vector<SensorSetting> DeriveSensorSettings(const SensorFacts& sensor,
                                                const OdometryConfig& scene);

/// The reference settings that depend on the sensor, applied after a shipped overlay of a reference
/// configuration: `esvo` (`aavio run --esvo`) takes ESVO's newest 1 000 events on rpg's DAVIS240C
/// (under 0.1 Mpx; 10 000 on DSEC's 640×480 are the overlay's), `paper` the ICRA code's 5 000 AA
/// samples there, of which mapping takes 1 000 (2 500 on DSEC's rig are the sensor's settings).
/// None for other overlays.
std::vector<SensorSetting> OverlaySensorSettings(const std::string& overlay,
                                                 const SensorFacts& sensor);

/// The settings as configuration entries, to apply before a preset's (each entry's origin names
/// its rule, for messages).
std::vector<ConfigEntry> ToConfigEntries(const std::vector<SensorSetting>& settings);

/// The preset a rig suggests when none is named, and why.
struct PresetSuggestion {
  std::string name;
  std::string reason;
};
PresetSuggestion SuggestPreset(const SensorFacts& sensor);

}  // namespace aavio::pipeline
