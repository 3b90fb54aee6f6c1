#pragma once
/// Levenberg–Marquardt on a camera pose (docs/tracking.md): one damped Gauss–Newton step at a
/// time on a least-squares cost of the pose, over the increment θ = (c, δ) of ApplyIncrement,
/// with the damping carried from step to step (the reference's) and the step clamped to a
/// tick's plausible motion. The registration drives it over mini-batches of the map.

#include <Eigen/Core>

#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::tracking {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Applies an increment θ = (c, δ) to T_ref_cur: R ← R(c) R, t ← δ + R(c) t, R re-orthonormalised.
geometry::RigidTransform ApplyIncrement(const geometry::RigidTransform& T_ref_cur,
                                        const Vector6d& theta);

/// A least-squares cost of the pose: its value, and its normal equations for θ.
class PoseCost {
 public:
  struct Linearization {
    double cost = 0.0;  ///< the cost at the pose
    Matrix6d H;         ///< JᵀJ (Gauss–Newton)
    Vector6d g;         ///< Jᵀr
  };
  virtual ~PoseCost() = default;
  virtual Linearization Linearize(const geometry::RigidTransform& T) const = 0;
  virtual double Cost(const geometry::RigidTransform& T) const = 0;
};

/// How one step went.
struct LmStep {
  bool accepted = false;              ///< a damping lowered the cost: the pose moved
  bool small_reduction = false;       ///< ... by less than function_tolerance of the cost
  Vector6d theta = Vector6d::Zero();  ///< the increment taken
};

class PoseLevenbergMarquardt {
 public:
  struct Options {
    double max_cayley_step = 0.02;         ///< ≈ 2.3° per step
    double max_translation_step_m = 0.05;  ///< per step
    double function_tolerance = 1e-3;      ///< a relative cost reduction this small is "small"
    int max_attempts = 6;                  ///< dampings tried per step (λ ×10 each)
  };
  PoseLevenbergMarquardt() = default;
  explicit PoseLevenbergMarquardt(const Options& options) : options_(options) {}

  /// Linearises `cost` at *T and tries dampings until one lowers it: then *T moves (λ ÷10).
  LmStep Step(const PoseCost& cost, geometry::RigidTransform* T);

 private:
  Options options_;
  double lambda_ = 1e-4;
};

}  // namespace aavio::tracking
