#pragma once
/// How well an estimate's velocity matches the ground truth's (docs/evaluation.md): the relative
/// velocity error of the EvSLAM benchmark and its area under the success curve, beside plain
/// RMS errors. Velocities are compared in each trajectory's own body frame, so no alignment
/// enters (both trajectories must describe the same body, as for every velocity benchmark).

#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/velocity.hpp"

namespace aavio::eval {

struct VelocityError {
  std::size_t pairs = 0;
  /// EvSLAM: RVE_i = |v_gt,i − v_est,i| / |v_gt,i| (0 where the truth stands still); the success
  /// rate S(ξ) = Σ |v_gt,i|·[RVE_i < ξ] / Σ |v_gt,i| over ξ ∈ [0, 1] (500 points), and AUC its
  /// trapezoid area (1 = every velocity exact, 0 = all off by their own size or more).
  double auc = 0.0;
  double rve_median = 0.0;
  double linear_rmse_mps = 0.0;   ///< |v_gt − v_est|
  double angular_rmse_dps = 0.0;  ///< |ω_gt − ω_est|, degrees per second
  double gt_speed_median_mps = 0.0;
};

/// Pairs each estimated velocity with the ground-truth velocity nearest in time within
/// `max_dt_ns` (both sorted; invalid velocities skipped). No pair: pairs = 0 and zeros.
VelocityError EvaluateVelocities(const std::vector<geometry::StampedVelocity>& estimate,
                                 const std::vector<geometry::StampedVelocity>& ground_truth,
                                 TimeNs max_dt_ns);

}  // namespace aavio::eval
