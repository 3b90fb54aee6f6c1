#pragma once
/// Trajectory accuracy as the field measures it (rpg_trajectory_evaluation, evo; the formulas are
/// in docs/evaluation.md): association of estimated and ground-truth poses by timestamp, the
/// absolute trajectory error (ATE: translation and rotation of the aligned estimate against ground
/// truth) and a relative pose error over a fixed time step (the per-tick drift `aavio run` reports;
/// the distance-based RPE of the papers is relative_error.hpp).

#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/eval/alignment.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::eval {

/// Pairs of estimated and ground-truth poses whose stamps differ by at most `max_dt_ns`, chosen
/// greedily closest first with every pose used at most once (the TUM `associate.py` rule that
/// rpg_trajectory_evaluation uses), in time order. Both inputs time-ordered. InvalidArgument when
/// nothing associates (e.g. no time overlap).
Expected<std::vector<PosePair>> Associate(const std::vector<geometry::StampedPose>& estimate,
                                          const std::vector<geometry::StampedPose>& ground_truth,
                                          TimeNs max_dt_ns = 20'000'000);

struct TrajectoryError {
  std::size_t pairs = 0;
  double path_length_m = 0.0;  ///< of the ground truth over the pairs
  double ate_rmse_m = 0.0, ate_mean_m = 0.0, ate_median_m = 0.0, ate_max_m = 0.0;
  double ate_rotation_rmse_deg = 0.0;  ///< angle of R_gtᵀ·R_align·R_est
  /// How far the positions pin down the alignment's rotation: ATE rmse over the spread of the
  /// aligned ground-truth positions across the worst axis (radians, in degrees; 0 without a
  /// rotation in the alignment, capped at 180). A path that barely leaves a line or a point
  /// leaves the rotation free, and ate_rotation_rmse_deg then measures the alignment.
  double alignment_rotation_sigma_deg = 0.0;
  /// Rotation error with the orientations aligned by their mean offset alone (the rotation
  /// R minimising Σ‖R_gt − R·R_est‖², whatever the positions): orientation drift, free of how
  /// well the path pins the position alignment.
  double ate_rotation_rmse_orientation_aligned_deg = 0.0;
  std::vector<double> ate_per_pair_m;  ///< translation error of each pair after alignment
  double rpe_step_s = 0.0;             ///< the relative pose error's time step
  double rpe_translation_rmse_m = 0.0, rpe_rotation_rmse_deg = 0.0;
  Similarity alignment;
};

/// ATE after `alignment`, and RPE between pairs `rpe_step_s` apart (nearest pair at or after).
TrajectoryError EvaluateTrajectory(const std::vector<PosePair>& pairs, Alignment alignment,
                                   double rpe_step_s = 0.1, int align_num_frames = -1);

}  // namespace aavio::eval
