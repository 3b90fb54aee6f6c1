// Levenberg–Marquardt on a pose: it reaches the minimum of a pose cost, clamps its steps to a
// tick's plausible motion, says when the reduction became small, and leaves the pose where no
// damping lowers the cost.
#include "aavio/tracking/pose_lm.hpp"

#include <gtest/gtest.h>

#include "aavio/geometry/rotation.hpp"

namespace aavio::tracking {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// ‖log(R R*ᵀ)‖² + ‖t − t*‖², with the Jacobian of its residuals for θ = (c, δ) at θ = 0:
// R ← R(c) R turns log(R R*ᵀ) by ≈ 2c, t ← δ + R(c) t moves t by δ + 2 c × t.
class DistanceToPose final : public PoseCost {
 public:
  explicit DistanceToPose(const geometry::RigidTransform& target) : target_(target) {}
  Linearization Linearize(const geometry::RigidTransform& T) const override {
    Eigen::Matrix<double, 6, 1> r;
    r << geometry::LogSO3(T.R * target_.R.transpose()), T.t - target_.t;
    Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
    J.topLeftCorner<3, 3>() = 2.0 * Eigen::Matrix3d::Identity();
    J.bottomLeftCorner<3, 3>() = -2.0 * Skew(T.t);
    J.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity();
    return {r.squaredNorm(), J.transpose() * J, J.transpose() * r};
  }
  double Cost(const geometry::RigidTransform& T) const override {
    return geometry::LogSO3(T.R * target_.R.transpose()).squaredNorm() +
           (T.t - target_.t).squaredNorm();
  }

 private:
  geometry::RigidTransform target_;
};

TEST(PoseLevenbergMarquardt, ReachesTheMinimumInClampedSteps) {
  const geometry::RigidTransform target(geometry::ExpSO3(Eigen::Vector3d(0.1, -0.2, 0.3)),
                                        Eigen::Vector3d(0.5, -0.2, 1.0));
  geometry::RigidTransform T(geometry::ExpSO3(Eigen::Vector3d(0.1, -0.2, 0.3 + 0.09)),
                             Eigen::Vector3d(0.6, -0.2, 1.0));  // 5° and 10 cm away
  const DistanceToPose cost(target);
  PoseLevenbergMarquardt lm;
  LmStep first = lm.Step(cost, &T);
  ASSERT_TRUE(first.accepted);
  EXPECT_LE(first.theta.head<3>().norm(), 0.02 + 1e-12);  // ≈ 2.3°, not the 5° asked
  EXPECT_LE(first.theta.tail<3>().norm(), 0.05 + 1e-12);
  EXPECT_FALSE(first.small_reduction);
  bool converged = false;
  for (int k = 0; k < 40 && !converged; ++k) {
    const LmStep step = lm.Step(cost, &T);
    converged = !step.accepted || step.small_reduction;
  }
  EXPECT_TRUE(converged);
  EXPECT_LT(geometry::LogSO3(T.R * target.R.transpose()).norm(), 1e-3);
  EXPECT_LT((T.t - target.t).norm(), 1e-3);
}

TEST(PoseLevenbergMarquardt, LeavesThePoseWhereNothingLowersTheCost) {
  const geometry::RigidTransform target(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 3));
  geometry::RigidTransform T = target;  // at the minimum
  PoseLevenbergMarquardt lm({.max_attempts = 3});
  const LmStep step = lm.Step(DistanceToPose(target), &T);
  EXPECT_FALSE(step.accepted);
  EXPECT_EQ(T.t, target.t);
  EXPECT_EQ(T.R, target.R);
}

TEST(PoseLevenbergMarquardt, ApplyIncrementTurnsAndMovesInTheReferenceFrame) {
  const geometry::RigidTransform T(geometry::ExpSO3(Eigen::Vector3d(0.0, 0.2, 0.0)),
                                   Eigen::Vector3d(1.0, 0.0, 0.0));
  Vector6d theta = Vector6d::Zero();
  theta.tail<3>() = Eigen::Vector3d(0.0, 0.5, 0.0);
  EXPECT_TRUE(ApplyIncrement(T, theta).t.isApprox(Eigen::Vector3d(1.0, 0.5, 0.0)));
  theta.setZero();
  theta(2) = 0.1;  // Cayley about z: R(c) = a turn of 2·atan(0.1)
  const geometry::RigidTransform turned = ApplyIncrement(T, theta);
  const Eigen::Matrix3d Rc = geometry::CayleyToRotation(Eigen::Vector3d(0.0, 0.0, 0.1));
  EXPECT_TRUE(turned.R.isApprox(Rc * T.R, 1e-12));
  EXPECT_TRUE(turned.t.isApprox(Rc * T.t, 1e-12));
  EXPECT_NEAR(geometry::LogSO3(Rc).norm(), 2.0 * std::atan(0.1), 1e-12);
}

}  // namespace
}  // namespace aavio::tracking
