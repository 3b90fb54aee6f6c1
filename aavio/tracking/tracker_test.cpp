#include "aavio/tracking/tracker.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "aavio/geometry/rotation.hpp"
#include "aavio/tracking/synthetic_scene.hpp"

namespace aavio::tracking {
namespace {

using testing::EdgeMap;
using testing::kCamera;
using testing::Render;

double RotationDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return geometry::LogSO3(a.transpose() * b).norm() * 180.0 / M_PI;
}

TEST(PredictPose, ConstantVelocityAndGyroRotation) {
  geometry::RigidTransform prevprev, prev;
  prevprev.R = geometry::ExpSO3(Eigen::Vector3d(0, 0.01, 0));
  prevprev.t = {0, 0, 1};
  prev.R = geometry::ExpSO3(Eigen::Vector3d(0, 0.03, 0));
  prev.t = {0.1, 0, 1.2};
  // Without a gyroscope: both by constant velocity.
  const geometry::RigidTransform cv = PredictPose(prev, prevprev, std::nullopt);
  EXPECT_LT((cv.t - Eigen::Vector3d(0.2, 0, 1.4)).norm(), 1e-12);
  EXPECT_LT(RotationDeg(cv.R, geometry::ExpSO3(Eigen::Vector3d(0, 0.05, 0))), 1e-9);
  // With it: the rotation is the gyroscope's, the translation still constant velocity.
  const Eigen::Matrix3d dR = geometry::ExpSO3(Eigen::Vector3d(0.01, 0, 0));
  const geometry::RigidTransform gy = PredictPose(prev, prevprev, dR);
  EXPECT_LT(RotationDeg(gy.R, prev.R * dR), 1e-9);
  EXPECT_LT((gy.t - cv.t).norm(), 1e-12);
  // First tick: no velocity yet.
  const geometry::RigidTransform first = PredictPose(prev, std::nullopt, std::nullopt);
  EXPECT_LT((first.t - prev.t).norm(), 1e-12);
  // A given (smoothed) velocity replaces the last tick's for the translation only.
  const geometry::RigidTransform smoothed =
      PredictPose(prev, prevprev, std::nullopt, Eigen::Vector3d(0.02, 0.0, 0.0));
  EXPECT_LT((smoothed.t - Eigen::Vector3d(0.12, 0, 1.2)).norm(), 1e-12);
  EXPECT_LT(RotationDeg(smoothed.R, cv.R), 1e-9);
  TrackingConfig config;
  config.velocity_gain = 1.5;
  EXPECT_FALSE(config.Validate().ok());
  config.velocity_gain = 0.3;
  config.lost_velocity_decay = -0.1;
  const Status bad_decay = config.Validate();
  EXPECT_NE(bad_decay.message().find("lost_velocity_decay"), std::string::npos)
      << bad_decay.message();
}

// The camera turns with a growing rate ω_y = 6t rad/s (constant velocity lags behind) and moves
// sideways; the IMU is mounted rotated against the camera. 30 ticks at 100 Hz.
struct TrackRun {
  double max_rotation_error_deg = 0.0, max_prediction_error_deg = 0.0;
  double sum_prediction_error_deg = 0.0;
  int ok = 0;
  Eigen::Vector3d final_bias;
};

TrackRun TrackSequence(bool gyro_prior, imu::GyroBiasMode bias_mode,
                       const Eigen::Vector3d& true_bias) {
  const std::vector<Eigen::Vector3d> map_points = EdgeMap(11);
  const Eigen::Matrix3d R_imu_cam = geometry::ExpSO3(Eigen::Vector3d(0.3, -1.2, 2.0));
  auto pose_at = [](double t) {
    geometry::RigidTransform T;
    T.R = geometry::ExpSO3(Eigen::Vector3d(0, 3.0 * t * t, 0));
    T.t = {0.3 * t, 0, 0.1 * t};
    return T;
  };
  // Gyroscope at 1 kHz: the camera rate ω_cam = (0, 6t, 0) in the IMU frame, plus the bias.
  std::vector<imu::ImuSample> imu_samples;
  for (TimeNs t = 0; t <= 400 * kNsPerMs; t += kNsPerMs) {
    const Eigen::Vector3d w_cam(0, 6.0 * NsToSeconds(t), 0);
    imu_samples.push_back({t, R_imu_cam * w_cam + true_bias, Eigen::Vector3d::Zero()});
  }
  TrackingConfig config;
  config.max_iterations = 20;
  imu::ImuConfig imu_config;
  imu_config.mode = gyro_prior ? imu::ImuMode::kGyro : imu::ImuMode::kOff;
  imu_config.bias_mode = bias_mode;
  imu_config.online_window = 10;
  Tracker tracker(kCamera, config, imu_config,
                  geometry::RigidTransform{R_imu_cam, Eigen::Vector3d::Zero()}, 7);
  const TimeNs tick = 10 * kNsPerMs, start = 100 * kNsPerMs;
  tracker.Reset(start, pose_at(0.1));
  auto map = std::make_shared<TrackingMap>();
  map->T_world_ref = geometry::RigidTransform();
  map->points_world = map_points;
  tracker.SetMap(map);
  TrackRun run;
  for (TimeNs t = start + tick; t <= 400 * kNsPerMs; t += tick) {
    const testing::Images images = Render(map_points, pose_at(NsToSeconds(t)));
    events::Observation obs;
    obs.t_ns = t;
    obs.negative_ts_left = images.negative;
    obs.grad_u = images.du;
    obs.grad_v = images.dv;
    const TrackingResult r = tracker.Track(obs, images.valid, imu_samples);
    run.ok += r.status == TrackingStatus::kOk;
    const Eigen::Matrix3d truth = pose_at(NsToSeconds(t)).R;
    run.max_rotation_error_deg =
        std::max(run.max_rotation_error_deg, RotationDeg(r.T_world_cur.R, truth));
    run.sum_prediction_error_deg += RotationDeg(r.T_world_predicted.R, truth);
    run.max_prediction_error_deg =
        std::max(run.max_prediction_error_deg, RotationDeg(r.T_world_predicted.R, truth));
  }
  run.final_bias = tracker.gyro_bias();
  return run;
}

TEST(Tracker, FollowsAnAcceleratingTurnAndTheGyroPriorPredictsIt) {
  const TrackRun with = TrackSequence(true, imu::GyroBiasMode::kFixed, Eigen::Vector3d::Zero());
  const TrackRun without = TrackSequence(false, imu::GyroBiasMode::kFixed, Eigen::Vector3d::Zero());
  EXPECT_EQ(with.ok, 30);
  // The synthetic time surface marks edges at whole pixels (0.14° at f = 200 px).
  EXPECT_LT(with.max_rotation_error_deg, 0.3);
  // Pre-integration of an exact gyroscope predicts the rotation up to the previous tick's error;
  // constant velocity also misses the acceleration (6 rad/s² · (10 ms)² ≈ 0.034° per tick).
  EXPECT_LT(with.max_prediction_error_deg, 0.3);
  EXPECT_LT(with.sum_prediction_error_deg, 0.8 * without.sum_prediction_error_deg)
      << with.sum_prediction_error_deg << " vs " << without.sum_prediction_error_deg;
}

TEST(Tracker, OnlineBiasEstimateConverges) {
  const Eigen::Vector3d bias(0.02, -0.01, 0.015);
  const TrackRun run = TrackSequence(true, imu::GyroBiasMode::kOnline, bias);
  EXPECT_EQ(run.ok, 30);
  EXPECT_LT((run.final_bias - bias).norm(), 0.01) << run.final_bias.transpose();
}

TEST(Tracker, DivergenceHoldsThePredictionAndReportsLost) {
  const std::vector<Eigen::Vector3d> map_points = EdgeMap(5);
  Tracker tracker(kCamera, TrackingConfig{}, imu::ImuConfig{}, geometry::RigidTransform{}, 1);
  tracker.Reset(0, geometry::RigidTransform());
  auto map = std::make_shared<TrackingMap>();
  map->points_world = map_points;
  tracker.SetMap(map);
  // The events show a view 8° away while the gyroscope says the camera stood still.
  geometry::RigidTransform seen;
  seen.R = geometry::ExpSO3(Eigen::Vector3d(0, 8.0 * M_PI / 180.0, 0));
  const testing::Images images = Render(map_points, seen);
  events::Observation obs;
  obs.t_ns = 10 * kNsPerMs;
  obs.negative_ts_left = images.negative;
  obs.grad_u = images.du;
  obs.grad_v = images.dv;
  const std::vector<imu::ImuSample> still = {
      {0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()},
      {20 * kNsPerMs, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
  const TrackingResult r = tracker.Track(obs, images.valid, still);
  EXPECT_EQ(r.status, TrackingStatus::kLost);
  EXPECT_LT(RotationDeg(r.T_world_cur.R, Eigen::Matrix3d::Identity()), 1e-9);
  // Without a map: the prediction, reported as such.
  Tracker unmapped(kCamera, TrackingConfig{}, imu::ImuConfig{}, geometry::RigidTransform{}, 1);
  unmapped.Reset(0, geometry::RigidTransform());
  EXPECT_EQ(unmapped.Track(obs, images.valid, still).status, TrackingStatus::kNoMap);
}

// A lost tick coasts on the velocity of the tracked ones (a car does not stop because a
// registration failed), and so does a restart that keeps it; a plain restart forgets it. With
// lost_velocity_decay < 1 the velocity shrinks on each lost tick.
TEST(Tracker, LostTicksCoastOnTheVelocity) {
  const std::vector<Eigen::Vector3d> map_points = EdgeMap(5);
  TrackingConfig config;  // the presets' steps
  config.max_iterations = 20;
  config.polish_iterations = 3;
  auto map = std::make_shared<TrackingMap>();
  map->points_world = map_points;
  auto start = [&](double lost_velocity_decay) {
    config.lost_velocity_decay = lost_velocity_decay;
    auto t =
        std::make_unique<Tracker>(kCamera, config, imu::ImuConfig{}, geometry::RigidTransform{}, 1);
    t->Reset(0, geometry::RigidTransform());
    t->SetMap(map);
    return t;
  };
  const std::unique_ptr<Tracker> coasting_tracker = start(1.0);
  Tracker& tracker = *coasting_tracker;
  auto observe = [&](const geometry::RigidTransform& T, TimeNs t) {
    const testing::Images images = Render(map_points, T);
    events::Observation obs;
    obs.t_ns = t;
    obs.negative_ts_left = images.negative;
    obs.grad_u = images.du;
    obs.grad_v = images.dv;
    return std::pair{obs, images.valid};
  };
  geometry::RigidTransform moved;
  moved.t = {0.02, 0.0, 0.0};
  auto [first, valid] = observe(moved, 10 * kNsPerMs);
  const TrackingResult ok = tracker.Track(first, valid, {});
  ASSERT_EQ(ok.status, TrackingStatus::kOk);
  const double step = ok.T_world_cur.t.x();
  EXPECT_NEAR(step, 0.02, 0.003);
  // An impossible view (8° turned) twice: lost, and the pose moves on by the same step each time.
  geometry::RigidTransform turned;
  turned.R = geometry::ExpSO3(Eigen::Vector3d(0, 8.0 * M_PI / 180.0, 0));
  auto [bad, bad_valid] = observe(turned, 20 * kNsPerMs);
  // The view at 20 and 30 ms: both lost; the x of the two poses.
  auto lose_twice = [&bad = bad, &bad_valid = bad_valid](Tracker& t) {
    bad.t_ns = 20 * kNsPerMs;
    const TrackingResult first_lost = t.Track(bad, bad_valid, {});
    EXPECT_EQ(first_lost.status, TrackingStatus::kLost);
    bad.t_ns = 30 * kNsPerMs;
    const TrackingResult second_lost = t.Track(bad, bad_valid, {});
    EXPECT_EQ(second_lost.status, TrackingStatus::kLost);
    return std::pair{first_lost.T_world_cur.t.x(), second_lost.T_world_cur.t.x()};
  };
  const auto [x_lost, x_lost_again] = lose_twice(tracker);
  EXPECT_NEAR(x_lost, 2.0 * step, 1e-9);
  EXPECT_NEAR(x_lost_again, 3.0 * step, 1e-9);
  // Restarted at the held pose keeping the velocity (re-initialisation): still coasting.
  tracker.Reset(30 * kNsPerMs, tracker.Track(bad, bad_valid, {}).T_world_cur, true);
  tracker.SetMap(nullptr);
  bad.t_ns = 50 * kNsPerMs;
  const TrackingResult coasting = tracker.Track(bad, bad_valid, {});
  EXPECT_EQ(coasting.status, TrackingStatus::kNoMap);
  EXPECT_NEAR(coasting.T_world_cur.t.x(), 5.0 * step, 1e-9);
  // Without a map the velocity is forgotten afterwards, as after a plain restart.
  bad.t_ns = 60 * kNsPerMs;
  EXPECT_NEAR(tracker.Track(bad, bad_valid, {}).T_world_cur.t.x(), 5.0 * step, 1e-9);

  // lost_velocity_decay 0 (the rpg preset): the first lost tick still coasts, then the pose holds.
  const std::unique_ptr<Tracker> holding_tracker = start(0.0);
  Tracker& holding = *holding_tracker;
  ASSERT_EQ(holding.Track(first, valid, {}).status, TrackingStatus::kOk);
  const auto [x_held, x_held_again] = lose_twice(holding);
  EXPECT_NEAR(x_held, 2.0 * step, 1e-9);
  EXPECT_NEAR(x_held_again, 2.0 * step, 1e-9);
}

// velocity_gain 0 is ESVO's zero-motion model: each tick starts from the previous pose, rotation
// included; otherwise (no gyroscope) the rotation of the last tick is continued.
TEST(Tracker, ZeroMotionStartsEachTickAtThePreviousPose) {
  const std::vector<Eigen::Vector3d> map_points = EdgeMap(7);
  auto map = std::make_shared<TrackingMap>();
  map->points_world = map_points;
  auto pose_at = [](int tick) {
    geometry::RigidTransform T;
    T.R = geometry::ExpSO3(Eigen::Vector3d(0, 0.5 * tick * M_PI / 180.0, 0));
    T.t = {0.01 * tick, 0.0, 0.0};
    return T;
  };
  // The third tick's prediction after two tracked ticks of a steady turn.
  auto third_prediction = [&](double velocity_gain, geometry::RigidTransform* second) {
    TrackingConfig config;
    config.max_iterations = 20;
    config.velocity_gain = velocity_gain;
    Tracker tracker(kCamera, config, imu::ImuConfig{}, geometry::RigidTransform{}, 3);
    tracker.Reset(0, pose_at(0));
    tracker.SetMap(map);
    TrackingResult r;
    for (int tick = 1; tick <= 3; ++tick) {
      const testing::Images images = Render(map_points, pose_at(tick));
      events::Observation obs;
      obs.t_ns = tick * 10 * kNsPerMs;
      obs.negative_ts_left = images.negative;
      obs.grad_u = images.du;
      obs.grad_v = images.dv;
      if (tick == 3) *second = r.T_world_cur;
      r = tracker.Track(obs, images.valid, {});
      EXPECT_EQ(r.status, TrackingStatus::kOk) << tick;
    }
    return r.T_world_predicted;
  };
  geometry::RigidTransform second;
  const geometry::RigidTransform held = third_prediction(0.0, &second);
  EXPECT_LT(RotationDeg(held.R, second.R), 1e-9);
  EXPECT_LT((held.t - second.t).norm(), 1e-12);
  const geometry::RigidTransform continued = third_prediction(1.0, &second);
  EXPECT_NEAR(RotationDeg(continued.R, second.R), 0.5, 0.1);
  EXPECT_NEAR((continued.t - second.t).norm(), 0.01, 0.003);
}

// imu.mode full: 1.5 s tracked (but for 0.1 s of events that do not register), then 0.4 s
// without events, both carried on the IMU alone, then events again. The camera sways and moves
// forward; a perfect IMU on the camera, gravity along +y.
TEST(Tracker, FullImuCarriesStretchesTheEventsCannotRegisterAndTrackingResumes) {
  const std::vector<Eigen::Vector3d> map_points = EdgeMap(11);
  const Eigen::Vector3d gravity(0, 9.81, 0);
  auto pose_at = [](double t) {
    return geometry::RigidTransform(geometry::ExpSO3(Eigen::Vector3d(0, 0.3 * std::sin(t), 0)),
                                    {0.2 * std::sin(2 * t), 0.05 * std::sin(3 * t), 0.15 * t});
  };
  std::vector<imu::ImuSample> imu_samples;
  for (TimeNs t = 0; t <= 2200 * kNsPerMs; t += kNsPerMs) {
    const double s = NsToSeconds(t);
    const Eigen::Vector3d accel_world(-0.8 * std::sin(2 * s), -0.45 * std::sin(3 * s), 0.0);
    imu_samples.push_back({t, Eigen::Vector3d(0, 0.3 * std::cos(s), 0),
                           pose_at(s).R.transpose() * (accel_world - gravity)});
  }
  TrackingConfig config;
  config.max_iterations = 20;
  imu::ImuConfig imu_config;
  imu_config.mode = imu::ImuMode::kFull;
  Tracker tracker(kCamera, config, imu_config, geometry::RigidTransform{}, 7);
  const TimeNs tick = 10 * kNsPerMs, start = 100 * kNsPerMs;
  const TimeNs dark_from = 1600 * kNsPerMs, dark_to = 2000 * kNsPerMs;
  // Before it, 0.1 s whose events show a view 8° off (a blur, a flicker): they do not register.
  const TimeNs wrong_from = 1200 * kNsPerMs, wrong_to = 1300 * kNsPerMs;
  tracker.Reset(start, pose_at(0.1));
  auto map = std::make_shared<TrackingMap>();
  map->points_world = map_points;
  tracker.SetMap(map);
  int ok_before = 0, imu_only = 0, ok_after = 0, wrong_imu_only = 0;
  double bridge_error_m = 0.0, wrong_error_m = 0.0;
  for (TimeNs t = start + tick; t <= 2100 * kNsPerMs; t += tick) {
    const bool dark = t > dark_from && t <= dark_to;
    const bool wrong = t > wrong_from && t <= wrong_to;
    const geometry::RigidTransform truth = pose_at(NsToSeconds(t));
    geometry::RigidTransform seen = truth;
    if (wrong) seen.R = seen.R * geometry::ExpSO3(Eigen::Vector3d(0, 8.0 * M_PI / 180.0, 0));
    const testing::Images images = Render(map_points, seen);
    events::Observation obs;
    obs.t_ns = t;
    obs.negative_ts_left = images.negative;
    obs.grad_u = images.du;
    obs.grad_v = images.dv;
    obs.new_events_left = dark ? 0 : 5000;
    std::vector<imu::ImuSample> window;
    for (const imu::ImuSample& s : imu_samples)
      if (s.t_ns >= t - tick - kNsPerMs && s.t_ns <= t + kNsPerMs) window.push_back(s);
    const TrackingResult r = tracker.Track(obs, images.valid, window);
    if (dark) {
      EXPECT_EQ(r.status, TrackingStatus::kImuOnly) << NsToSeconds(t);
      imu_only += r.status == TrackingStatus::kImuOnly;
      if (t == dark_to) bridge_error_m = (r.T_world_cur.t - truth.t).norm();
    } else if (wrong) {
      EXPECT_EQ(r.status, TrackingStatus::kImuOnly) << NsToSeconds(t);
      wrong_imu_only += r.status == TrackingStatus::kImuOnly;
      wrong_error_m = std::max(wrong_error_m, (r.T_world_cur.t - truth.t).norm());
    } else {
      (t <= dark_from ? ok_before : ok_after) += r.status == TrackingStatus::kOk;
    }
  }
  ASSERT_TRUE(tracker.imu_state().has_value());
  EXPECT_EQ(wrong_imu_only, 10);
  EXPECT_LT(wrong_error_m, 0.005);  // it moved 2 cm meanwhile
  EXPECT_EQ(ok_before, 140);
  EXPECT_EQ(imu_only, 40);
  EXPECT_EQ(ok_after, 10);  // resumed at once, on the same map
  // Holding the pose would be off by the 8 cm travelled in the dark.
  const double travelled = (pose_at(2.0).t - pose_at(1.6).t).norm();
  EXPECT_GT(travelled, 0.07);
  EXPECT_LT(bridge_error_m, 0.1 * travelled) << bridge_error_m << " m after " << travelled;
  // The gravity it found, in the camera's world.
  EXPECT_LT((tracker.imu_state()->gravity_world - gravity).norm(), 0.1);
}

}  // namespace
}  // namespace aavio::tracking
