#pragma once
/// Alignment of an estimated trajectory to ground truth before the absolute error is taken
/// (docs/evaluation.md §2): Umeyama's least-squares fit of the associated positions, as
/// rpg_trajectory_evaluation and evo do it — se3 (rotation + translation; stereo VO), sim3 (with
/// scale; monocular), posyaw (translation + rotation about the world z axis only; VIO, where
/// gravity fixes roll and pitch), none.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"
#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::eval {

/// One estimated pose and the ground-truth pose associated with it.
struct PosePair {
  TimeNs t_ns = 0;
  geometry::RigidTransform T_world_est, T_world_gt;
};

enum class Alignment { kNone, kSe3, kSim3, kPosYaw };

/// "none", "se3", "sim3", "posyaw".
const char* AlignmentName(Alignment alignment);
Expected<Alignment> ParseAlignment(const std::string& name);

/// p_gt ≈ scale · R · p_est + t.
struct Similarity {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double scale = 1.0;
  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const { return scale * (R * p) + t; }
};

/// The transform S minimising Σ|p_gt − S(p_est)|² over the first `num_frames` pairs (all when
/// ≤ 0 or more than there are): Umeyama 1991 for se3/sim3; for posyaw R = Rz(θ) with
/// θ = atan2(C01 − C10, C00 + C11), C = Σ (p_est − μ_est)(p_gt − μ_gt)ᵀ, scale 1. With fewer than
/// 3 pairs (2 for posyaw) the identity.
Similarity Align(const std::vector<PosePair>& pairs, Alignment alignment, int num_frames = -1);

}  // namespace aavio::eval
