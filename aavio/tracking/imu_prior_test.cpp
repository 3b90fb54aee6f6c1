// The IMU's prior for a tick: the gyroscope's rotation (in the camera frame when the mode uses
// it), and in full mode the back-end's pose and how long a tick may be carried on it.
#include "aavio/tracking/imu_prior.hpp"

#include <gtest/gtest.h>

#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/imu_test_motion.hpp"

namespace aavio::tracking {
namespace {

namespace tm = imu::test_motion;

constexpr TimeNs kTickNs = 10 * kNsPerMs;

std::vector<imu::ImuSample> Window(const std::vector<imu::ImuSample>& all, TimeNs from_ns,
                                   TimeNs to_ns) {
  std::vector<imu::ImuSample> window;
  for (const imu::ImuSample& s : all)
    if (s.t_ns >= from_ns - kNsPerMs && s.t_ns <= to_ns + kNsPerMs) window.push_back(s);
  return window;
}

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return geometry::LogSO3(a.transpose() * b).norm() * 180.0 / M_PI;
}

imu::ImuConfig WithTrueBias(imu::ImuMode mode) {
  imu::ImuConfig config;
  config.mode = mode;
  config.gyro_bias_rad_s = {tm::kGyroBias.x(), tm::kGyroBias.y(), tm::kGyroBias.z()};
  return config;
}

TEST(ImuPrior, TheGyroscopeRotationInTheCameraFrame) {
  const tm::Motion motion;
  const std::vector<imu::ImuSample> samples = tm::Imu(motion, 1.0, 3);
  ImuPrior prior(WithTrueBias(imu::ImuMode::kGyro), tm::kImuCam);
  const TimeNs t0 = 500 * kNsPerMs, t1 = t0 + kTickNs;
  prior.Restart(t0, motion.WorldCam(0.5));
  const TickPrior tick = prior.ForTick(Window(samples, t0, t1), t0, t1, motion.WorldCam(0.5), 0.0);
  ASSERT_TRUE(tick.delta_R_imu && tick.delta_R_cam);
  // It turns 0.3° in the tick; the gyroscope's noise over it is about 0.01°.
  const Eigen::Matrix3d truth_cam = motion.WorldCam(0.5).R.transpose() * motion.WorldCam(0.51).R;
  EXPECT_GT(AngleDeg(truth_cam, Eigen::Matrix3d::Identity()), 0.2);
  EXPECT_LT(AngleDeg(*tick.delta_R_imu, motion.R(0.5).transpose() * motion.R(0.51)), 0.05);
  EXPECT_LT(AngleDeg(*tick.delta_R_cam, truth_cam), 0.05);
  // Gyroscope mode has no back-end: no pose, nothing carried.
  EXPECT_FALSE(tick.T_world_cur);
  EXPECT_FALSE(tick.can_bridge || tick.can_bridge_divergence || tick.at_rest);
  EXPECT_EQ(prior.gyro_bias(), tm::kGyroBias);
  EXPECT_FALSE(prior.state());
}

TEST(ImuPrior, ModeOffGivesNoPriorAndNoSamplesNoRotation) {
  const tm::Motion motion;
  const std::vector<imu::ImuSample> samples = tm::Imu(motion, 1.0, 3);
  ImuPrior off(WithTrueBias(imu::ImuMode::kOff), tm::kImuCam);
  off.Restart(0, {});
  const TickPrior tick = off.ForTick(Window(samples, 0, kTickNs), 0, kTickNs, {}, 0.0);
  EXPECT_TRUE(tick.delta_R_imu);  // measured (the online bias may use it), not used
  EXPECT_FALSE(tick.delta_R_cam);
  ImuPrior gyro(WithTrueBias(imu::ImuMode::kGyro), tm::kImuCam);
  gyro.Restart(0, {});
  const TickPrior none = gyro.ForTick({}, 0, kTickNs, {}, 0.0);
  EXPECT_FALSE(none.delta_R_imu || none.delta_R_cam);
}

TEST(ImuPrior, FullModePredictsThePoseAndBoundsTheBridge) {
  const tm::Motion motion;
  const std::vector<imu::ImuSample> samples = tm::Imu(motion, 3.0, 5);
  imu::ImuConfig config = WithTrueBias(imu::ImuMode::kFull);
  ImuPrior prior(config, tm::kImuCam);
  std::mt19937_64 rng(9);
  TimeNs t_prev = 0;
  geometry::RigidTransform T_prev = motion.WorldCam(0.0);
  prior.Restart(0, T_prev);
  TickPrior tick;
  // 2.5 s of registered ticks: the back-end solves its window.
  for (TimeNs t = kTickNs; t <= 2500 * kNsPerMs; t += kTickNs) {
    tick = prior.ForTick(Window(samples, t_prev, t), t_prev, t, T_prev, 0.0);
    T_prev = tm::Tracked(motion, NsToSeconds(t), rng);
    prior.AddPose(t, T_prev, /*registered=*/true);
    t_prev = t;
  }
  ASSERT_TRUE(prior.state());
  ASSERT_TRUE(tick.T_world_cur);
  const TimeNs t = t_prev + kTickNs;
  const TickPrior next = prior.ForTick(Window(samples, t_prev, t), t_prev, t, T_prev, 0.1);
  ASSERT_TRUE(next.T_world_cur);
  EXPECT_LT((next.T_world_cur->t - motion.WorldCam(NsToSeconds(t)).t).norm(), 0.01);
  EXPECT_LT(AngleDeg(next.T_world_cur->R, motion.WorldCam(NsToSeconds(t)).R), 0.5);
  EXPECT_FALSE(next.at_rest);  // it moves at about 1 m/s
  EXPECT_TRUE(next.can_bridge && next.can_bridge_divergence);
  // Long without registration: missing events are carried up to max_bridge_s, events that do
  // not register for half a second.
  const TickPrior later = prior.ForTick({}, t, t + kTickNs, *next.T_world_cur, 0.6);
  EXPECT_TRUE(later.can_bridge);
  EXPECT_FALSE(later.can_bridge_divergence);
  const TickPrior too_late =
      prior.ForTick({}, t + kTickNs, t + 2 * kTickNs, *next.T_world_cur, config.max_bridge_s + 0.1);
  EXPECT_FALSE(too_late.can_bridge || too_late.can_bridge_divergence);
}

}  // namespace
}  // namespace aavio::tracking
