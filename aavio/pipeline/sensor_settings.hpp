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
  /// Under 0.1 Mpx (DAVIS240C 43 kpx, DAVIS346 90 kpx; VGA is 307 kpx): the reference
  /// configurations differ in the same way between rpg and DSEC.
  bool small() const;
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

/// A configuration file's section whose keys apply only on a small sensor (SensorFacts::small):
/// where a reference's settings differ between rpg's DAVIS240C and larger sensors (the esvo and
/// paper overlays' sample budgets).
inline constexpr char kSmallSensorSection[] = "small_sensor";

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
