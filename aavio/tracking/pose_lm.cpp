#include "aavio/tracking/pose_lm.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "aavio/geometry/rotation.hpp"

namespace aavio::tracking {

geometry::RigidTransform ApplyIncrement(const geometry::RigidTransform& T_ref_cur,
                                        const Vector6d& theta) {
  const Eigen::Matrix3d Rc = geometry::CayleyToRotation(theta.head<3>());
  return {geometry::Orthonormalize(Rc * T_ref_cur.R),
          Eigen::Vector3d(theta.tail<3>() + Rc * T_ref_cur.t)};
}

LmStep PoseLevenbergMarquardt::Step(const PoseCost& cost, geometry::RigidTransform* T) {
  const PoseCost::Linearization at = cost.Linearize(*T);
  LmStep step;
  for (int attempt = 0; attempt < options_.max_attempts; ++attempt) {
    Matrix6d A = at.H;
    A.diagonal() += lambda_ * at.H.diagonal() + Vector6d::Constant(1e-9);
    Vector6d theta = A.ldlt().solve(-at.g);
    // A step larger than a tick's plausible motion comes from a degenerate batch (few edges,
    // flat surface): shorten it rather than jump (Cayley c ≈ θ/2).
    const double scale = std::max({1.0, theta.head<3>().norm() / options_.max_cayley_step,
                                   theta.tail<3>().norm() / options_.max_translation_step_m});
    theta /= scale;
    const geometry::RigidTransform trial = ApplyIncrement(*T, theta);
    const double trial_cost = cost.Cost(trial);
    if (trial_cost < at.cost) {
      *T = trial;
      lambda_ = std::max(1e-7, lambda_ * 0.1);
      step.accepted = true;
      step.small_reduction = (at.cost - trial_cost) / at.cost < options_.function_tolerance;
      step.theta = theta;
      return step;
    }
    lambda_ *= 10.0;
  }
  return step;
}

}  // namespace aavio::tracking
