// The IMU's prior for a tick: the gyroscope's rotation (in the camera frame when the mode uses
// it), a standstill, and in full mode the back-end's pose and how long a tick may be carried on it.
#include "aavio/tracking/imu_prior.hpp"

#include <gtest/gtest.h>

#include <random>

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

// Readings of an IMU that does not turn and accelerates by `a_world(t)` (noise and biases of a
// consumer IMU at 1 kHz, as tm::Imu's), over [0, t_end_s].
template <typename Accel>
std::vector<imu::ImuSample> StillImu(double t_end_s, const Accel& a_world) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Matrix3d R_world_imu = tm::Motion{}.R(0.0);
  std::vector<imu::ImuSample> samples;
  for (TimeNs t = 0; t <= SecondsToNs(t_end_s); t += kNsPerMs) {
    samples.push_back({t, tm::kGyroBias + 0.003 * geometry::DrawZyx(n, rng),
                       R_world_imu.transpose() * (a_world(NsToSeconds(t)) - tm::kGravity) +
                           tm::kAccelBias + 0.12 * geometry::DrawZyx(n, rng)});
  }
  return samples;
}

// Ticks from 0 to t_end_s, the camera's tracked position at `position(t)` (registered unless
// held): the first tick and the last that hold (-1 if none).
template <typename Position>
std::pair<double, double> HeldTicks(ImuPrior& prior, const std::vector<imu::ImuSample>& samples,
                                    double t_end_s, const Position& position) {
  const Eigen::Matrix3d R = tm::Motion{}.WorldCam(0.0).R;
  geometry::RigidTransform T_prev(R, position(0.0));
  prior.Restart(0, T_prev);
  double first = -1.0, last = -1.0;
  for (TimeNs t = kTickNs; t <= SecondsToNs(t_end_s); t += kTickNs) {
    const TickPrior tick =
        prior.ForTick(Window(samples, t - kTickNs, t), t - kTickNs, t, T_prev, 0);
    EXPECT_TRUE(!tick.hold || tick.at_rest);
    if (tick.hold) {
      EXPECT_TRUE(tick.T_world_cur && tick.T_world_cur->t == T_prev.t);
      if (first < 0.0) first = NsToSeconds(t);
      last = NsToSeconds(t);
      prior.AddPose(t, T_prev, /*registered=*/false);
    } else {
      T_prev = geometry::RigidTransform(R, position(NsToSeconds(t)));
      prior.AddPose(t, T_prev, /*registered=*/true);
    }
  }
  return {first, last};
}

TEST(ImuPrior, GyroModeHoldsAStandstillUntilTheCameraMovesOff) {
  ImuPrior prior(WithTrueBias(imu::ImuMode::kGyro), tm::kImuCam);
  // Still for 1.5 s, then pulling away smoothly at 0.5 m/s² without turning: what the readings
  // alone (gravity and a little more, steady) would take for rest.
  const Eigen::Vector3d away = Eigen::Vector3d(1, 1, 0).normalized();
  const auto accel = [&](double t) -> Eigen::Vector3d {
    return t < 1.5 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5 * away);
  };
  const auto position = [&](double t) -> Eigen::Vector3d {
    return Eigen::Vector3d(0.3, -0.1, 0.2) + (t < 1.5 ? 0.0 : 0.25 * (t - 1.5) * (t - 1.5)) * away;
  };
  const std::vector<imu::ImuSample> samples = StillImu(2.0, accel);
  const auto [first, last] = HeldTicks(prior, samples, 2.0, position);
  // Held once the tracked poses have shown 0.2 s of no motion, until the readings change (the
  // last held tick is 1.54 s: the step of 0.5 m/s² shows within a few readings).
  EXPECT_NEAR(first, 0.21, 0.015);
  EXPECT_GT(last, 1.5);
  EXPECT_LT(last, 1.6);
  // Pulling away at 0.1 m/s², under that change: the velocity integrated since the standstill
  // began ends it within a second (at most 5 cm gone; 2.22 s, 0.72 s after, with this noise).
  ImuPrior gentle(WithTrueBias(imu::ImuMode::kGyro), tm::kImuCam);
  const auto slow_accel = [&](double t) -> Eigen::Vector3d {
    return t < 1.5 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.1 * away);
  };
  const auto slow_position = [&](double t) -> Eigen::Vector3d {
    return Eigen::Vector3d(0.3, -0.1, 0.2) + (t < 1.5 ? 0.0 : 0.05 * (t - 1.5) * (t - 1.5)) * away;
  };
  const double slow_last = HeldTicks(gentle, StillImu(3.5, slow_accel), 3.5, slow_position).second;
  EXPECT_GT(slow_last, 1.9);
  EXPECT_LT(slow_last, 2.5);
  // The same readings while the tracked camera moves steadily at 1 m/s: never held.
  ImuPrior moving(WithTrueBias(imu::ImuMode::kGyro), tm::kImuCam);
  const auto steady = [](double t) -> Eigen::Vector3d { return {t, 0, 0}; };
  const std::vector<imu::ImuSample> still =
      StillImu(1.0, [](double) { return Eigen::Vector3d::Zero(); });
  EXPECT_EQ(HeldTicks(moving, still, 1.0, steady).first, -1.0);
  // Full mode leaves the standstill to its back-end; mode off knows none.
  for (const imu::ImuMode mode : {imu::ImuMode::kFull, imu::ImuMode::kOff}) {
    ImuPrior other(WithTrueBias(mode), tm::kImuCam);
    const auto rest = [](double) { return Eigen::Vector3d(0.3, -0.1, 0.2); };
    EXPECT_EQ(HeldTicks(other, still, 1.0, rest).first, -1.0);
  }
}

}  // namespace
}  // namespace aavio::tracking
