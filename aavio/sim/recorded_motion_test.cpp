#include "aavio/sim/recorded_motion.hpp"

#include <gtest/gtest.h>

namespace aavio::sim {
namespace {

using geometry::ExpSO3;

/// A car on a z-up road driving a left curve at 8 m/s; the camera looks along travel with +y
/// down, and the recorded body frame is that camera turned 180° about its optical axis (DSEC).
std::vector<geometry::StampedPose> DsecLikeRecording(const Eigen::Matrix3d& R_cam_body) {
  std::vector<geometry::StampedPose> poses;
  for (int k = 0; k <= 100; ++k) {  // 5 Hz for 20 s
    const double t = 0.2 * k;
    const double heading = 0.03 * t;  // rad, turning left
    const Eigen::Vector3d forward(std::cos(heading), std::sin(heading), 0.0);
    const Eigen::Vector3d down(0, 0, -1);
    Eigen::Matrix3d R_world_cam;
    R_world_cam.col(2) = forward;
    R_world_cam.col(1) = down;
    R_world_cam.col(0) = down.cross(forward);
    // Position integrated along the heading at 8 m/s: (8/a)(sin at, 1 − cos at) for a = 0.03.
    const Eigen::Vector3d p(100 + 8.0 / 0.03 * std::sin(heading),
                            50 + 8.0 / 0.03 * (1 - std::cos(heading)), 3);
    poses.push_back({SecondsToNs(36475.17 + t), {R_world_cam * R_cam_body, p}});
  }
  return poses;
}

TEST(RecordedMotion, DrivingRuleKeepsTheCameraUprightAndLookingAhead) {
  // Body frames as DSEC has them (camera turned 180° about its optical axis), a camera-like one
  // and an arbitrary one. The camera must end up level, +z along travel and +y along the
  // vertical (either sense: see DrivingBodyToCamera), with gravity on the side of its +y.
  const std::vector<Eigen::Matrix3d> body_frames = {ExpSO3(Eigen::Vector3d(0, 0, M_PI)),
                                                    ExpSO3(Eigen::Vector3d(0.3, -1.2, 0.4)),
                                                    Eigen::Matrix3d::Identity()};
  for (const Eigen::Matrix3d& R_cam_body : body_frames) {
    const auto recorded = DsecLikeRecording(R_cam_body);
    Expected<CameraPath> path = CameraPathFromRecording(recorded, 0.0, 0.0, "auto");
    ASSERT_TRUE(path.ok()) << path.status().message();
    EXPECT_NE(path->body_to_camera.find("driving rule"), std::string::npos);
    const Eigen::Vector3d down = path->gravity_world.normalized();
    for (std::size_t i = 0; i + 1 < path->poses.size(); ++i) {
      const Eigen::Matrix3d& R = path->poses[i].T_world_body.R;
      EXPECT_GT(R.col(1).dot(down), std::cos(0.02)) << i;  // +y toward the ground
      const Eigen::Vector3d travel =
          (path->poses[i + 1].T_world_body.t - path->poses[i].T_world_body.t).normalized();
      EXPECT_GT(R.col(2).dot(travel), std::cos(0.05)) << i;  // +z along the motion
      EXPECT_LT(std::abs(travel.dot(down)), 0.02) << i;      // a level road
    }
    EXPECT_LT(path->poses.front().T_world_body.t.norm(), 1e-12);  // relative to the first pose
    EXPECT_NEAR(path->gravity_world.norm(), 9.81, 1e-12);
  }
}

TEST(RecordedMotion, HandHeldPathsKeepTheirFrameAndCropping) {
  std::vector<geometry::StampedPose> recorded;
  for (int k = 0; k <= 400; ++k) {  // 2 s at 200 Hz, within a metre
    recorded.push_back(
        {1518196259772284031LL + k * 5'000'000LL,
         {ExpSO3(Eigen::Vector3d(0.01 * k, 0, 0)), Eigen::Vector3d(0.001 * k, 0, 0)}});
  }
  Expected<CameraPath> path = CameraPathFromRecording(recorded, 0.5, 1.0, "auto");
  ASSERT_TRUE(path.ok());
  EXPECT_EQ(path->body_to_camera, "identity");
  EXPECT_EQ(path->poses.size(), 201u);
  EXPECT_EQ(path->poses.front().t_ns, recorded[100].t_ns);
  EXPECT_FALSE(CameraPathFromRecording(recorded, 5.0, 1.0, "auto").ok());
  EXPECT_NE(CameraPathFromRecording(recorded, 0, 0, "sideways")
                .status()
                .message()
                .find("identity, driving or auto"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::sim
