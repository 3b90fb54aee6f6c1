#include "aavio/eval/trajectory_error.hpp"

#include <gtest/gtest.h>

#include "aavio/geometry/rotation.hpp"

namespace aavio::eval {
namespace {

std::vector<geometry::StampedPose> Spiral(TimeNs t0, TimeNs step, int n) {
  std::vector<geometry::StampedPose> poses;
  for (int i = 0; i < n; ++i) {
    const double s = 0.05 * i;
    geometry::RigidTransform T;
    T.R = geometry::ExpSO3(Eigen::Vector3d(0.1 * std::sin(s), s, 0.2 * s));
    T.t = {std::cos(s), std::sin(s), 0.1 * s};
    poses.push_back({t0 + i * step, T});
  }
  return poses;
}

TEST(TrajectoryError, AlignmentRecoversAKnownTransformAndScale) {
  const auto gt = Spiral(0, 10 * kNsPerMs, 200);
  geometry::RigidTransform M;
  M.R = geometry::ExpSO3(Eigen::Vector3d(0.3, -0.5, 1.1));
  M.t = {2.0, -1.0, 0.5};
  auto moved = gt, scaled = gt;
  for (auto& p : moved)
    p.T_world_body = M * p.T_world_body;
  for (auto& p : scaled) {
    p.T_world_body = M * p.T_world_body;
    p.T_world_body.t *= 2.5;
  }
  const auto se3 = EvaluateTrajectory(*Associate(moved, gt), Alignment::kSe3);
  EXPECT_LT(se3.ate_rmse_m, 1e-9);
  EXPECT_LT(se3.ate_rotation_rmse_deg, 1e-6);
  EXPECT_LT((se3.alignment.R - M.R.transpose()).norm(), 1e-9);
  EXPECT_LT(se3.rpe_translation_rmse_m, 1e-9);
  const auto sim3 = EvaluateTrajectory(*Associate(scaled, gt), Alignment::kSim3);
  EXPECT_LT(sim3.ate_rmse_m, 1e-9);
  EXPECT_NEAR(sim3.alignment.scale, 1.0 / 2.5, 1e-9);
  // se3 cannot undo a scale; no alignment cannot undo the motion.
  EXPECT_GT(EvaluateTrajectory(*Associate(scaled, gt), Alignment::kSe3).ate_rmse_m, 0.1);
  EXPECT_GT(EvaluateTrajectory(*Associate(moved, gt), Alignment::kNone).ate_rmse_m, 1.0);
}

// How far the positions fix the alignment's rotation, and the rotation error free of it.
TEST(TrajectoryError, AlignmentRotationUncertaintyAndOrientationAlignedError) {
  // A straight line leaves the rotation about it free; a spiral a metre wide pins it.
  std::vector<geometry::StampedPose> line;
  for (int i = 0; i < 100; ++i) {
    geometry::RigidTransform T;
    T.t = {0.01 * i, 0.0, 0.0};
    line.push_back({i * 10 * kNsPerMs, T});
  }
  auto noisy_line = line;
  for (std::size_t i = 0; i < noisy_line.size(); ++i)
    noisy_line[i].T_world_body.t.y() += (i % 2 ? 0.002 : -0.002);
  const auto straight = EvaluateTrajectory(*Associate(noisy_line, line), Alignment::kSe3);
  EXPECT_NEAR(straight.alignment_rotation_sigma_deg, 180.0, 1e-9);  // no spread across the line
  const auto gt = Spiral(0, 10 * kNsPerMs, 200);
  auto est = gt;
  geometry::RigidTransform M;  // a constant frame offset, and 1 cm of noise
  M.R = geometry::ExpSO3(Eigen::Vector3d(0.2, 0.0, 0.4));
  for (std::size_t i = 0; i < est.size(); ++i) {
    est[i].T_world_body = M * est[i].T_world_body;
    est[i].T_world_body.t.z() += (i % 2 ? 0.01 : -0.01);
  }
  const auto spiral = EvaluateTrajectory(*Associate(est, gt), Alignment::kSe3);
  // ATE 1 cm over a spread of ~0.7 m across the worst axis: under a degree.
  EXPECT_GT(spiral.alignment_rotation_sigma_deg, 0.2);
  EXPECT_LT(spiral.alignment_rotation_sigma_deg, 1.5);
  // The orientations differ by M alone: aligned by their mean offset, none is left.
  EXPECT_LT(spiral.ate_rotation_rmse_orientation_aligned_deg, 1e-6);
  EXPECT_EQ(EvaluateTrajectory(*Associate(est, gt), Alignment::kNone).alignment_rotation_sigma_deg,
            0.0);
}

TEST(TrajectoryError, HandComputedErrors) {
  // Ground truth along x at 1 m/s; the estimate is 3 cm off in y for every second pose.
  std::vector<geometry::StampedPose> gt, est;
  for (int i = 0; i <= 10; ++i) {
    geometry::RigidTransform T;
    T.t = {0.1 * i, 0, 0};
    gt.push_back({i * 100 * kNsPerMs, T});
    T.t.y() = i % 2 ? 0.03 : 0.0;
    est.push_back({i * 100 * kNsPerMs, T});
  }
  const auto e = EvaluateTrajectory(*Associate(est, gt), Alignment::kNone, 0.1);
  EXPECT_NEAR(e.ate_rmse_m, std::sqrt(5.0 * 0.03 * 0.03 / 11.0), 1e-12);
  EXPECT_NEAR(e.ate_max_m, 0.03, 1e-12);
  EXPECT_NEAR(e.rpe_translation_rmse_m, 0.03, 1e-12);  // every 0.1 s step is 3 cm off
  EXPECT_NEAR(e.path_length_m, 1.0, 1e-12);
}

TEST(TrajectoryError, AssociationGapsRatesAndNoOverlap) {
  const auto gt = Spiral(0, 5 * kNsPerMs, 400);               // 200 Hz
  const auto est = Spiral(3 * kNsPerMs, 10 * kNsPerMs, 100);  // 100 Hz, 3 ms later
  const auto pairs = Associate(est, gt);
  ASSERT_TRUE(pairs.ok());
  EXPECT_EQ(pairs->size(), 100u);
  // A gap in the ground truth: estimates in it are left out.
  std::vector<geometry::StampedPose> gapped;
  for (const auto& p : gt)
    if (p.t_ns < 200 * kNsPerMs || p.t_ns > 600 * kNsPerMs) gapped.push_back(p);
  EXPECT_LT(Associate(est, gapped)->size(), 70u);
  const auto late = Spiral(100 * 1'000'000'000LL, 10 * kNsPerMs, 10);
  const auto none = Associate(late, gt);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message().find("overlap"), std::string::npos);
}

}  // namespace
}  // namespace aavio::eval
