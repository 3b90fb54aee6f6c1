#include "aavio/eval/velocity_error.hpp"

#include <gtest/gtest.h>

namespace aavio::eval {
namespace {

std::vector<geometry::StampedVelocity> Constant(const Eigen::Vector3d& v, int n, TimeNs step) {
  std::vector<geometry::StampedVelocity> out(n);
  for (int i = 0; i < n; ++i)
    out[i] = {i * step, v, Eigen::Vector3d::Zero(), true};
  return out;
}

TEST(VelocityError, AucOfExactHalfOffAndWeightedErrors) {
  const auto gt = Constant({1, 0, 0}, 100, 10 * kNsPerMs);
  // Exact: S(ξ) = 1 for every ξ > 0 (S(0) = 0: RVE < 0 never holds), AUC = 1 − 1/499/2.
  const VelocityError exact = EvaluateVelocities(gt, gt, kNsPerMs);
  EXPECT_EQ(exact.pairs, 100u);
  EXPECT_NEAR(exact.auc, 1.0 - 0.5 / 499, 1e-12);
  EXPECT_EQ(exact.linear_rmse_mps, 0.0);
  // Every estimate 0.5 m/s off a 1 m/s truth: RVE 0.5, S steps from 0 to 1 at ξ = 0.5.
  const VelocityError half =
      EvaluateVelocities(Constant({1.5, 0, 0}, 100, 10 * kNsPerMs), gt, kNsPerMs);
  EXPECT_NEAR(half.auc, 0.5, 2.0 / 499);
  EXPECT_NEAR(half.rve_median, 0.5, 1e-12);
  EXPECT_NEAR(half.linear_rmse_mps, 0.5, 1e-12);
  // Off by their own size or more: AUC 0.
  EXPECT_NEAR(EvaluateVelocities(Constant({-1, 0, 0}, 100, 10 * kNsPerMs), gt, kNsPerMs).auc, 0.0,
              1e-12);
  // Stamps that do not meet within the window: no pair, no score.
  auto late = gt;
  for (auto& v : late)
    v.t_ns += 5 * kNsPerMs;
  EXPECT_EQ(EvaluateVelocities(late, gt, kNsPerMs).pairs, 0u);
}

}  // namespace
}  // namespace aavio::eval
