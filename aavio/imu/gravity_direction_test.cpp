#include "aavio/imu/gravity_direction.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::imu {
namespace {

// A camera swinging on a circle (bounded velocity), its world tilted against gravity: the
// accelerometer's specific force, turned by the tracked orientations, averages to −g.
TEST(GravityDirection, FoundFromTheAccelerometerAndTheOrientations) {
  const Eigen::Matrix3d R_true_world =  // the run's world as seen from a z-up one
      geometry::ExpSO3(Eigen::Vector3d(0.4, -0.3, 1.0));
  const Eigen::Vector3d g_true(0, 0, -9.81);
  const Eigen::Matrix3d R_imu_cam = geometry::ExpSO3(Eigen::Vector3d(0.1, 0.2, -0.1));
  std::vector<geometry::StampedPose> trajectory;
  GravityDirectionEstimator estimator;
  for (int k = 0; k <= 5000; ++k) {  // 5 s at 1 kHz
    const double t = k * 1e-3;
    geometry::RigidTransform T_true_cam;  // in the z-up world
    T_true_cam.R =
        geometry::ExpSO3(Eigen::Vector3d(0.3 * std::sin(2 * t), 0.2 * std::cos(3 * t), t));
    T_true_cam.t = {std::cos(2 * t), std::sin(2 * t), 0.1 * std::sin(t)};
    const Eigen::Vector3d a(-4 * std::cos(2 * t), -4 * std::sin(2 * t), -0.1 * std::sin(t));
    const Eigen::Matrix3d R_true_imu = T_true_cam.R * R_imu_cam.transpose();
    ImuSample s;
    s.t_ns = k * kNsPerMs;
    s.accel_m_s2 = R_true_imu.transpose() * (a - g_true);
    estimator.Add(s);
    if (k % 10 == 0) {
      geometry::RigidTransform T_world_cam = T_true_cam;
      T_world_cam.R = R_true_world.transpose() * T_true_cam.R;
      T_world_cam.t = R_true_world.transpose() * T_true_cam.t;
      trajectory.push_back({s.t_ns, T_world_cam});
    }
  }
  const std::optional<GravityDirection> g = estimator.Estimate(trajectory, R_imu_cam);
  ASSERT_TRUE(g.has_value());
  const Eigen::Vector3d down_true = R_true_world.transpose() * Eigen::Vector3d(0, 0, -1);
  // 1.6 turns leave a mean acceleration of ~0.8 m/s² (~4.5°), which the ends' velocities remove.
  EXPECT_LT(std::acos(std::min(1.0, g->down_world.dot(down_true))), 0.2 * M_PI / 180);
  EXPECT_NEAR(g->magnitude_m_s2, 9.81, 0.05);
  EXPECT_LT((g->R_up_world() * g->down_world - Eigen::Vector3d(0, 0, -1)).norm(), 1e-9);
  // Too short a run: nothing.
  EXPECT_FALSE(estimator
                   .Estimate(std::vector<geometry::StampedPose>(trajectory.begin(),
                                                                trajectory.begin() + 100),
                             R_imu_cam)
                   .has_value());
}

}  // namespace
}  // namespace aavio::imu
