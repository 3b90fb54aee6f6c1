#pragma once
/// The relative pose error over sub-trajectories of fixed travelled distance, as
/// rpg_trajectory_evaluation computes it (Zhang & Scaramuzza, IROS 2018; formulas in
/// docs/evaluation.md §4), and the ESVO papers' summary of it: translation error in % of the
/// distance and rotation error in °/m, RMSE pooled over all lengths.
///
/// For each length L and each start pair i, the end pair j is the one whose ground-truth distance
/// from the start is closest to d_i + L, within 0.2·L. With the estimate's relative motion
/// E = T_est,iᴵ·T_est,j (translation × the alignment's scale) and the ground truth's
/// G = T_gt,iᴵ·T_gt,j, the error is Δ = G⁻¹·E expressed in the estimate's world orientation
/// (R_est,j·Δ·R_est,jᵀ): translation error |t_Δ| [m] and |t_Δ|/L·100 [%], rotation error
/// angle(R_Δ) [°] and angle/L [°/m], yaw error from the z-y-x Euler angles of the rotated Δ.

#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/eval/alignment.hpp"
#include "aavio/eval/error_statistics.hpp"

namespace aavio::eval {

struct RelativeErrorConfig {
  /// Sub-trajectory lengths as fractions of the ground truth's path length (rpg's default
  /// boxplot percentages), each truncated to centimetres as rpg does.
  std::vector<double> fractions = {0.1, 0.2, 0.3, 0.4, 0.5};
  /// Fixed lengths [m]; when not empty they replace `fractions` (e.g. the KITTI-style 100…800 m).
  std::vector<double> lengths_m;
  /// An end pair is accepted only if its distance is within this fraction of L (rpg: 0.2).
  double max_length_error_fraction = 0.2;

  Status Validate() const;
};

struct SubTrajectoryErrors {
  double length_m = 0.0;
  std::vector<double> start_distance_m;  ///< ground-truth distance from the start of each sample
  std::vector<double> trans_m, trans_pct, rot_deg, rot_deg_per_m, yaw_deg;
  ErrorStatistics trans_m_stats, trans_pct_stats, rot_deg_stats, rot_deg_per_m_stats,
      yaw_deg_stats;
};

struct RelativeError {
  std::vector<SubTrajectoryErrors> per_length;
  /// The ESVO papers' form: RMSE of the translation error [%] and of the rotation error [°/m]
  /// over the samples of all lengths.
  double trans_pct_rmse = 0.0, rot_deg_per_m_rmse = 0.0;
  std::size_t samples = 0;
};

/// `pairs` time-ordered; `path_length_m` the length the fractions refer to (rpg: of the whole
/// ground-truth file); `scale` the alignment's (1 for se3). Lengths with fewer than 2 samples are
/// reported empty, as rpg does ("too few samples").
RelativeError ComputeRelativeError(const std::vector<PosePair>& pairs, double path_length_m,
                                   double scale, const RelativeErrorConfig& config);

/// Ground-truth distance travelled from the first pair to each pair.
std::vector<double> DistanceFromStart(const std::vector<PosePair>& pairs);

}  // namespace aavio::eval
