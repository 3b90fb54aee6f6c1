#include "aavio/config/sensor_rules.hpp"

#include <algorithm>
#include <cmath>

#include "aavio/common/format.hpp"

namespace aavio::config {

namespace {

// Below it a sensor is "small" (DAVIS240C: 43 kpx, DAVIS346: 90 kpx), above "large" (VGA:
// 307 kpx, 1280×720: 922 kpx). The reference configurations differ in the same way between
// rpg and DSEC.
constexpr long kSmallSensorPixels = 100000;
// Above it, the per-pixel work of a tick (render, rectify, filter, derive the time surface)
// outweighs the events': ticks come at 40 Hz, ESVO2's rate for TUM-VIE's 1280×720 cameras.
constexpr long kHighResolutionPixels = 500000;
// The σ of a depth, in pixels of disparity at the middle of the depth range, beyond which
// refinement culls it: 0.51 px is both rpg's 3.5 % and DSEC's 10 %.
constexpr double kMaxDisparityStddevPx = 0.51;
// Refinement culls a depth whose σ_ρ exceeds ESVO's rpg stdVar_vis_threshold, 0.015 1/m — but
// σ_ρ is a disparity σ divided by f·b, so on a narrow rig that value asks a precision static
// stereo cannot give: 0.12 px of a 5 cm DAVIS240C pair, which then keeps 1 match in 100. The
// cull never asks more than 0.2 px (ESVO's value asks 0.35 px of the rpg pair and 0.23 px of the
// 160×120 mini rig, which both keep theirs).
constexpr double kEsvoMaxInvDepthStddev = 0.015;
constexpr double kMinDisparityStddevPx = 0.2;
// Baselines from here up are cars' (DSEC 0.6 m, KITTI 0.54 m); hand-held, drone and robot rigs
// are 0.1–0.2 m (rpg 0.15, MVSEC 0.10, TUM-VIE 0.12, VECtor 0.17).
constexpr double kDrivingBaselineM = 0.3;

// `value` to `digits` significant digits, exactly as a configuration file holding its printed
// text reads back: a run configured from its written config.yaml is the same run.
double Significant(double value, int digits) {
  double parsed = 0.0;
  (void)config_detail::ParseDouble(StrFormat("%.*g", digits, value), &parsed);
  return parsed;
}

std::string Text(bool v) {
  return v ? "true" : "false";
}
std::string Text(int v) {
  return std::to_string(v);
}
std::string Text(double v) {
  return FieldChecker::Num(v);
}

// Sets the fields no source set and keeps what each rule gave.
class Rules {
 public:
  explicit Rules(const std::set<std::string>& set_by_sources) : set_by_sources_(set_by_sources) {}

  template <typename T>
  void Set(const char* key, T& field, T value, std::string rule) {
    const bool applied = !set_by_sources_.contains(key);
    if (applied) field = value;
    rulings_.push_back({key, Text(value), std::move(rule), applied});
  }
  std::vector<SensorRuling> rulings() { return std::move(rulings_); }

 private:
  const std::set<std::string>& set_by_sources_;
  std::vector<SensorRuling> rulings_;
};

}  // namespace

SensorFacts SensorFacts::Of(const geometry::StereoRig& rig) {
  return {rig.width(), rig.height(), rig.focal_px(), rig.baseline_m()};
}

bool SensorFacts::small() const {
  return static_cast<long>(width_px) * height_px < kSmallSensorPixels;
}

std::string SensorFacts::Describe() const {
  return StrFormat("%d x %d px, f %.1f px, baseline %.4f m (f*b %.1f px*m)", width_px, height_px,
                   focal_px, baseline_m, focal_px * baseline_m);
}

std::vector<SensorRuling> ApplySensorRules(const SensorFacts& sensor,
                                           const std::set<std::string>& set_by_sources,
                                           pipeline::OdometryConfig* config) {
  Rules r(set_by_sources);
  const int w = sensor.width_px, h = sensor.height_px;
  const bool small = sensor.small();
  const std::string size = small ? "under 0.1 Mpx" : "0.1 Mpx or more";

  const bool high = static_cast<long>(w) * h > kHighResolutionPixels;
  r.Set("time_surface.rate_hz", config->time_surface.rate_hz, high ? 40.0 : 100.0,
        high ? "over 0.5 Mpx: 40 Hz (ESVO2 TUM-VIE), a tick's per-pixel work is 3x VGA's"
             : "up to 0.5 Mpx: 100 Hz (paper, ESVO)");

  const int aa_rows = static_cast<int>(std::max(1L, std::lround(8.0 * h / w)));
  r.Set("adaptive_accumulation.grid_cols", config->adaptive_accumulation.grid_cols, 8,
        "the paper's 8 blocks across (30 px at 240 px, 80 px at 640 px)");
  r.Set("adaptive_accumulation.grid_rows", config->adaptive_accumulation.grid_rows, aa_rows,
        StrFormat("square blocks: 8 x %d / %d", h, w));

  const int cols = static_cast<int>(std::max(4L, std::lround(w / 80.0)));
  const int rows = static_cast<int>(std::max(3L, std::lround(h / 80.0)));
  r.Set("edge_sampling.grid_cols", config->edge_sampling.grid_cols, cols,
        StrFormat("~80 px sampling blocks (ICRA code), at least 4 x 3 (ESVO2 rpg): "
                  "max(4, %d / 80)",
                  w));
  r.Set("edge_sampling.grid_rows", config->edge_sampling.grid_rows, rows,
        StrFormat("max(3, %d / 80), as the columns", h));

  const int budget = small ? 2000 : 2500;
  const std::string budget_rule = size +
                                  (small ? ": 2000 (ESVO2 rpg)" : ": the paper's 2500 (DSEC)") +
                                  "; the cost grows with the samples, not the pixels";
  r.Set("edge_sampling.num_points", config->edge_sampling.num_points, budget, budget_rule);
  r.Set("mapping.max_points", config->mapping.max_points, budget, "as edge_sampling.num_points");
  r.Set("edge_sampling.min_spacing_px", config->edge_sampling.min_spacing_px, small ? 0 : 2,
        size + (small ? ": 0, every sample goes where the edges are"
                      : ": 2 px, so that the budget does not crowd the strongest edges"));
  r.Set("mapping.static_stereo.smooth_time_surface",
        config->mapping.static_stereo.smooth_time_surface, !small,
        size + (small ? ": off (ESVO rpg)" : ": on (ESVO, ESVO2 DSEC)"));

  mapping::DepthRefinementConfig& refinement = config->mapping.depth_refinement;
  const double fb = sensor.focal_px * sensor.baseline_m;
  if (fb > 0.0) {
    const double stddev = std::max(kEsvoMaxInvDepthStddev, kMinDisparityStddevPx / fb);
    r.Set("mapping.depth_refinement.max_inv_depth_stddev", refinement.max_inv_depth_stddev,
          Significant(stddev, 3),
          StrFormat("ESVO rpg's 0.015 1/m, or 0.2 px of disparity where f*b is under "
                    "13.3 px*m: max(0.015, 0.2 / f*b %.1f px*m)",
                    fb));
  }

  const double rho_mid = std::sqrt(config->mapping.inv_depth_min * config->mapping.inv_depth_max);
  const double disparity_mid_px = fb * rho_mid;
  const double relative = kMaxDisparityStddevPx / disparity_mid_px;
  // No rule without a depth range (the configuration's validation names that key instead).
  if (!std::isfinite(relative) || relative <= 0.0) return r.rulings();
  r.Set("mapping.depth_refinement.max_relative_stddev", refinement.max_relative_stddev,
        Significant(relative, 2),
        StrFormat("a depth known to 0.51 px of disparity at the middle of the depth "
                  "range: 0.51 / (f*b %.1f x %.3g 1/m = %.1f px)",
                  fb, rho_mid, disparity_mid_px));
  return r.rulings();
}

PresetSuggestion SuggestPreset(const SensorFacts& sensor) {
  if (sensor.baseline_m >= kDrivingBaselineM) {
    return {"driving", StrFormat("baseline %.2f m >= 0.3 m: a car's rig", sensor.baseline_m)};
  }
  return {"indoor",
          StrFormat("baseline %.2f m < 0.3 m: a hand-held, drone or robot rig", sensor.baseline_m)};
}

}  // namespace aavio::config
