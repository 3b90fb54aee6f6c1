#include "aavio/geometry/rigid_transform.hpp"

#include <gtest/gtest.h>

#include <random>

#include "aavio/geometry/random_draws.hpp"

namespace aavio::geometry {
namespace {

RigidTransform RandomTransform(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d R = ExpSO3(DrawZyx(u, rng) * 2.0);
  return {R, DrawZyx(u, rng) * 5.0};
}

double Distance(const RigidTransform& a, const RigidTransform& b) {
  return (a.Matrix() - b.Matrix()).cwiseAbs().maxCoeff();
}

TEST(RigidTransform, ComposeAndInverse) {
  std::mt19937 rng(11);
  for (int i = 0; i < 100; ++i) {
    const RigidTransform T_a_b = RandomTransform(rng);
    const RigidTransform T_b_c = RandomTransform(rng);
    const Eigen::Vector3d p_c(0.3, -2.0, 4.0);
    EXPECT_LT(((T_a_b * T_b_c) * p_c - T_a_b * (T_b_c * p_c)).norm(), 1e-12);
    EXPECT_LT(Distance(T_a_b * T_a_b.Inverse(), RigidTransform::Identity()), 1e-12);
    EXPECT_LT(Distance(RigidTransform::FromMatrix(T_a_b.Matrix()), T_a_b), 0.0 + 1e-15);
  }
}

TEST(RigidTransform, ExpLogRoundTrip) {
  std::mt19937 rng(5);
  for (int i = 0; i < 100; ++i) {
    const RigidTransform T = RandomTransform(rng);
    EXPECT_LT(Distance(ExpSE3(LogSE3(T)), T), 1e-10);
  }
  Eigen::Matrix<double, 6, 1> twist;
  twist << 1, 2, 3, 0, 0, 0;  // pure translation
  EXPECT_LT((ExpSE3(twist).t - Eigen::Vector3d(1, 2, 3)).norm(), 1e-15);
}

TEST(RigidTransform, InterpolationIsSlerpPlusLinear) {
  const RigidTransform a(ExpSO3(Eigen::Vector3d(0, 0, 0.2)), Eigen::Vector3d(0, 0, 0));
  const RigidTransform b(ExpSO3(Eigen::Vector3d(0, 0, 1.0)), Eigen::Vector3d(2, 4, -2));
  const RigidTransform mid = InterpolatePose(a, b, 0.25);
  EXPECT_LT((LogSO3(mid.R) - Eigen::Vector3d(0, 0, 0.4)).norm(), 1e-12);
  EXPECT_LT((mid.t - Eigen::Vector3d(0.5, 1, -0.5)).norm(), 1e-12);
  EXPECT_LT(Distance(InterpolatePose(a, b, 0.0), a), 1e-12);
  EXPECT_LT(Distance(InterpolatePose(a, b, 1.0), b), 1e-12);
  // Extrapolation continues the same constant-rate rotation.
  const RigidTransform beyond = InterpolatePose(a, b, 1.5);
  EXPECT_LT((LogSO3(beyond.R) - Eigen::Vector3d(0, 0, 1.4)).norm(), 1e-12);
  EXPECT_LT((beyond.t - Eigen::Vector3d(3, 6, -3)).norm(), 1e-12);
}

}  // namespace
}  // namespace aavio::geometry
