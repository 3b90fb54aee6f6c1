#pragma once
/// Trajectory accuracy as the field measures it (rpg_trajectory_evaluation, evo):
/// association of estimated and ground-truth poses by nearest timestamp, Umeyama alignment
/// (se3: rotation + translation; sim3: with scale; none), the absolute trajectory error (ATE:
/// translation of the aligned estimate against ground truth) and the relative pose error over a
/// fixed time step. (The full set — posyaw alignment, sub-trajectory RPE by travelled distance —
/// comes with `aavio eval`, docs/evaluation.md.)

#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::eval {

struct PosePair {
  TimeNs t_ns = 0;
  geometry::RigidTransform T_world_est, T_world_gt;
};

/// Each estimate with the ground-truth pose nearest in time, if within `max_dt_ns`; both inputs
/// time-ordered. InvalidArgument when nothing associates (e.g. no time overlap).
Expected<std::vector<PosePair>> Associate(const std::vector<geometry::StampedPose>& estimate,
                                          const std::vector<geometry::StampedPose>& ground_truth,
                                          TimeNs max_dt_ns = 20'000'000);

enum class Alignment { kNone, kSe3, kSim3 };

struct Similarity {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double scale = 1.0;
  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const { return scale * (R * p) + t; }
};

/// The transform S minimising Σ|p_gt − S(p_est)|² over the positions (Umeyama 1991).
Similarity Align(const std::vector<PosePair>& pairs, Alignment alignment);

struct TrajectoryError {
  std::size_t pairs = 0;
  double path_length_m = 0.0;  ///< of the ground truth over the pairs
  double ate_rmse_m = 0.0, ate_mean_m = 0.0, ate_median_m = 0.0, ate_max_m = 0.0;
  double ate_rotation_rmse_deg = 0.0;
  double rpe_step_s = 0.0;  ///< the relative pose error's time step
  double rpe_translation_rmse_m = 0.0, rpe_rotation_rmse_deg = 0.0;
  Similarity alignment;
};

/// ATE after `alignment`, and RPE between pairs `rpe_step_s` apart (nearest pair at or after).
TrajectoryError EvaluateTrajectory(const std::vector<PosePair>& pairs, Alignment alignment,
                                   double rpe_step_s = 0.1);

}  // namespace aavio::eval
