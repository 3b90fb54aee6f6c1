#pragma once
/// Configuration of tracking: registration of the local map on the negative time surface
/// (docs/tracking.md).

#include "aavio/common/config_fields.hpp"

namespace aavio::tracking {

struct TrackingConfig {
  int max_points = 2000;    ///< map points sampled per registration problem [paper ~2k]
  int batch_size = 300;     ///< points per LM step (≥ max_points: all points, plain LM)
  int min_map_points = 50;  ///< fewer map points than this: no tracking (kNoMap)
  int max_iterations = 10;  ///< LM steps per tick ([ICRA], [ESVO]; ESVO2 rpg 20)
  /// aavio: LM steps on all points after the mini-batches (0 = the reference)
  int polish_iterations = 0;
  double huber_threshold = 50.0;  ///< robust loss threshold [TS levels]
  /// Registration results further than this from the prediction count as divergence (aavio; the
  /// reference has no such test): rotation [deg] and translation [m] per tick.
  double max_correction_deg = 3.0;
  double max_correction_m = 0.3;
  /// Translation prediction: the velocity per tick is v ← g·Δt + (1 − g)·v over tracked ticks
  /// (reset to 0 without a map). 1 = constant velocity of the last tick ([ICRA]); smaller values
  /// average the registration's noise out of the prediction; 0 = zero motion ([ESVO]): the
  /// previous pose is the prediction, its rotation too unless the gyroscope gives one.
  double velocity_gain = 1.0;
  /// aavio: on a lost tick the pose coasts on the velocity, which is then multiplied by this.
  /// 1 keeps it (a car does not stop because a registration failed); 0 holds the pose from the
  /// second lost tick on (hand-held: the velocity of the ticks before a loss is suspect — a
  /// registration that jumped 2–5 cm a tick before failing sent the pose away at metres/second).
  double lost_velocity_decay = 1.0;
  /// aavio: with the gyroscope prior, the registration also pays weight·‖δ‖² for the rotation δ
  /// [deg] between its estimate and the gyro-predicted rotation — a soft prior in units of the
  /// mean squared robust residual [TS levels² per deg²] (typically 10²–40² per point). 0 = the
  /// paper: the prediction is only the initial value (docs/tracking.md).
  double gyro_rotation_weight = 0.0;
  /// aavio: the predicted translation (constant velocity) as a soft prior: the registration also
  /// pays weight·‖Δt‖² for its translation Δt [cm] from the prediction, in the same units
  /// [TS levels² per cm²]. Holds weakly observed directions (motion along the optical axis, a
  /// flat cost valley) where mini-batch noise would slide the pose; 0 = the paper.
  double translation_prior_weight = 0.0;
  /// aavio: leave out of each tick's registration the map points where the current stereo pair
  /// sees something at another depth (stereo_check.hpp: people or cars passing near the
  /// camera). Builds the right time surface at every tick, not only at mapping ticks.
  bool stereo_check = false;

  template <typename V>
  void VisitFields(V&& v) {
    v("max_points", max_points, "map points sampled per registration");
    v("batch_size", batch_size, "points per Levenberg–Marquardt step (mini-batches)");
    v("min_map_points", min_map_points,
      "fewer map points than this: the tick is not tracked (no_map)");
    v("max_iterations", max_iterations, "Levenberg–Marquardt steps per tick");
    v("polish_iterations", polish_iterations, "then LM steps on all points (aavio)");
    v("huber_threshold", huber_threshold, "robust loss threshold [time-surface levels]");
    v("max_correction_deg", max_correction_deg,
      "a registration further than this from the prediction is lost [deg]");
    v("max_correction_m", max_correction_m, "... or further than this [m]");
    v("velocity_gain", velocity_gain,
      "constant-velocity smoothing: 1 last tick's velocity, 0 zero motion (ESVO)");
    v("lost_velocity_decay", lost_velocity_decay,
      "the velocity is multiplied by it on each lost tick (aavio)");
    v("gyro_rotation_weight", gyro_rotation_weight,
      "the gyroscope's rotation also as a cost term; 0 off (aavio)");
    v("translation_prior_weight", translation_prior_weight,
      "the predicted translation as a soft prior; 0 off (aavio)");
    v("stereo_check", stereo_check,
      "leave out map points the stereo pair now sees something nearer at (movers; aavio)");
  }
  Status Validate() const;
};

}  // namespace aavio::tracking
