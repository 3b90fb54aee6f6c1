#include "aavio/geometry/velocity.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::geometry {
namespace {

// A body on a circle of radius 1 m at 1 rad/s, turning with it (yaw rate 1 rad/s) and rolling
// at 0.5 rad/s: in its own frame its velocity is constant.
RigidTransform Circle(double t) {
  RigidTransform T;
  T.R = ExpSO3(Eigen::Vector3d(0, 0, t)) * ExpSO3(Eigen::Vector3d(0.5 * t, 0, 0));
  T.t = {std::cos(t), std::sin(t), 0.2 * t};
  return T;
}

std::vector<StampedPose> CirclePoses(TimeNs step, double seconds) {
  std::vector<StampedPose> poses;
  for (TimeNs t = 0; t <= SecondsToNs(seconds); t += step)
    poses.push_back({t, Circle(NsToSeconds(t))});
  return poses;
}

TEST(Velocity, RecoversTheBodyFrameVelocityOfAKnownMotion) {
  const std::vector<StampedPose> poses = CirclePoses(10 * kNsPerMs, 2.0);
  const std::vector<StampedVelocity> v = EstimateVelocities(poses, 20 * kNsPerMs);
  ASSERT_EQ(v.size(), poses.size());
  for (std::size_t i = 3; i + 3 < v.size(); i += 17) {  // (a one-sided window at the ends)
    const double t = NsToSeconds(poses[i].t_ns);
    const Eigen::Vector3d v_world(-std::sin(t), std::cos(t), 0.2);
    const Eigen::Vector3d expected = poses[i].T_world_body.R.transpose() * v_world;
    ASSERT_TRUE(v[i].valid);
    // A line through points of a circle: off by ~ω²·window²/6 of the speed at most.
    EXPECT_LT((v[i].v_body_mps - expected).norm(), 2e-3) << i;
    // Body-frame angular velocity: R(t)ᵀ·Ṙ(t) of Rz(t)·Rx(0.5t) = Rx(-0.5t)·ez + 0.5·ex.
    const Eigen::Vector3d w = ExpSO3(Eigen::Vector3d(-0.5 * t, 0, 0)) * Eigen::Vector3d::UnitZ() +
                              Eigen::Vector3d(0.5, 0, 0);
    EXPECT_LT((v[i].w_body_radps - w).norm(), 2e-3) << i;
  }
}

TEST(Velocity, TheNewestPoseFromThePosesBeforeIt) {
  const std::vector<StampedPose> poses = CirclePoses(10 * kNsPerMs, 1.0);
  const StampedVelocity v = NewestVelocity(poses, 100 * kNsPerMs);
  ASSERT_TRUE(v.valid);
  const double t = 1.0;
  const Eigen::Vector3d expected =
      poses.back().T_world_body.R.transpose() * Eigen::Vector3d(-std::sin(t), std::cos(t), 0.2);
  // A line through the last 100 ms of a circle at 1 rad/s: the chord's direction, ~0.05 rad off.
  EXPECT_LT((v.v_body_mps - expected).norm(), 0.06);
  EXPECT_GT((v.v_body_mps - expected).norm(), 0.02);
  EXPECT_FALSE(NewestVelocity({poses.front()}, 100 * kNsPerMs).valid);
}

TEST(Velocity, GapsSplitTheTrajectoryAndSamplingMissesThem) {
  std::vector<StampedPose> poses = CirclePoses(10 * kNsPerMs, 1.0);
  // A 200 ms gap, then the body stands still elsewhere.
  const std::size_t before = poses.size();
  for (int k = 0; k < 20; ++k) {
    RigidTransform T;
    T.t = {5, 5, 5};
    poses.push_back({SecondsToNs(1.2) + k * 10 * kNsPerMs, T});
  }
  const std::vector<StampedVelocity> v = EstimateVelocities(poses, 30 * kNsPerMs);
  // No velocity reaches across the gap: the still segment is still from its first pose.
  EXPECT_LT(v[before].v_body_mps.norm(), 1e-12);
  EXPECT_TRUE(v[before].valid);
  EXPECT_NEAR(v[before - 1].v_body_mps.norm(), std::hypot(1.0, 0.2), 1e-2);

  const std::vector<TimeNs> stamps = {-20 * kNsPerMs,  // before the start by two intervals: missing
                                      -5 * kNsPerMs,   // half an interval before: extrapolated
                                      SecondsToNs(0.505),  // between two poses
                                      SecondsToNs(1.1),    // inside the gap: missing
                                      SecondsToNs(1.2) + 5 * kNsPerMs};
  const Sampled s = SampleAt(poses, v, stamps);
  ASSERT_EQ(s.poses.size(), 3u);
  ASSERT_EQ(s.missing.size(), 2u);
  EXPECT_EQ(s.missing[0], stamps[0]);
  EXPECT_EQ(s.missing[1], stamps[3]);
  EXPECT_LT((s.poses[0].T_world_body.t - Circle(-0.005).t).norm(), 1e-4);
  EXPECT_LT((s.poses[1].T_world_body.t - Circle(0.505).t).norm(), 1e-4);
  EXPECT_NEAR(s.velocities[1].v_body_mps.norm(), std::hypot(1.0, 0.2), 1e-2);
  EXPECT_LT((s.poses[2].T_world_body.t - Eigen::Vector3d(5, 5, 5)).norm(), 1e-12);
}

}  // namespace
}  // namespace aavio::geometry
