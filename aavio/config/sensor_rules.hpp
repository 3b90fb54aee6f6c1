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
/// The rules run once, after every source (config_sources.hpp), on the fields no source set; a
/// rule that also depends on the scene (the σ_ρ/ρ culling, on the depth range) reads it from the
/// configuration the sources made.

#include <set>
#include <string>
#include <vector>

#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::config {

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

/// What one rule gave a key, and why.
struct SensorRuling {
  std::string key;
  std::string value;  ///< as a configuration file would hold it
  std::string rule;
  bool applied = true;  ///< false where a source had set the key, which then keeps its value
};

/// Sets every field the sensor decides, unless its key is in `set_by_sources`, and returns each
/// rule's value. The depth range is read from `config`; no other field of it is.
std::vector<SensorRuling> ApplySensorRules(const SensorFacts& sensor,
                                           const std::set<std::string>& set_by_sources,
                                           pipeline::OdometryConfig* config);

/// A configuration file's section whose keys apply only on a small sensor (SensorFacts::small):
/// where a reference's settings differ between rpg's DAVIS240C and larger sensors (the esvo and
/// paper overlays' sample budgets).
inline constexpr char kSmallSensorSection[] = "small_sensor";

/// The preset a rig suggests when none is named, and why.
struct PresetSuggestion {
  std::string name;
  std::string reason;
};
PresetSuggestion SuggestPreset(const SensorFacts& sensor);

}  // namespace aavio::config
