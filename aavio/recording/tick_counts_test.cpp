// What the ticks said, counted: statuses and lost reasons, registration stops, IMU-only stretches
// merged over consecutive ticks, bootstraps (the first one's time, failed attempts), cycles.
#include "aavio/recording/tick_counts.hpp"

#include <gtest/gtest.h>

namespace aavio::recording {
namespace {

using tracking::TrackingStatus;

pipeline::OdometryTick Tick(double t_s, TrackingStatus status) {
  pipeline::OdometryTick t;
  t.t_ns = SecondsToNs(t_s);
  t.status = status;
  return t;
}

TEST(TickCounts, CountsWhatTheTicksSaid) {
  TickCounts counts(SecondsToNs(1.0));
  pipeline::OdometryTick first = Tick(1.01, TrackingStatus::kNoMap);
  first.bootstrap_failure = "too few points";
  counts.AddTick(first);
  pipeline::OdometryTick boot = Tick(1.02, TrackingStatus::kNoMap);
  boot.bootstrap = boot.mapped = true;
  counts.AddTick(boot);
  for (double t : {1.03, 1.04}) {
    pipeline::OdometryTick ok = Tick(t, TrackingStatus::kOk);
    ok.registration_stop = tracking::RegistrationStop::kConverged;
    ok.stereo_left_out = t < 1.035 ? 30 : 0;
    counts.AddTick(ok);
  }
  for (double t : {1.05, 1.06, 1.07})  // one stretch on the IMU
    counts.AddTick(Tick(t, TrackingStatus::kImuOnly));
  pipeline::OdometryTick lost = Tick(1.08, TrackingStatus::kLost);
  lost.lost_reason = tracking::LostReason::kCostGrew;
  lost.registration_stop = tracking::RegistrationStop::kMaxIterations;
  lost.reinitialised = true;
  lost.dropped_events = 12;  // a running total
  counts.AddTick(lost);
  counts.AddTick(Tick(1.09, TrackingStatus::kImuOnly));  // a second stretch
  pipeline::OdometryTick skipped = Tick(1.10, TrackingStatus::kOk);
  skipped.mapping_skipped = true;
  skipped.dropped_events = 15;
  counts.AddTick(skipped);

  EXPECT_EQ(counts.status_counts().at("ok"), 3);
  EXPECT_EQ(counts.mapping_cycles(), 1);
  EXPECT_EQ(counts.dropped_events(), 15);
  nlohmann::json s;
  counts.AddTo(&s, SecondsToNs(1.01));
  EXPECT_EQ(s["status"]["imu"], 4);
  EXPECT_EQ(s["status"]["no_map"], 2);
  EXPECT_EQ(s["lost_reasons"]["cost_grew"], 1);
  EXPECT_EQ(s["registration_stops"]["converged"], 2);
  EXPECT_EQ(s["registration_stops"]["max_iterations"], 1);
  EXPECT_EQ(s["stereo_check"]["ticks_leaving_points_out"], 1);
  EXPECT_NEAR(s["stereo_check"]["points_left_out_per_registration"].get<double>(), 10.0, 1e-12);
  ASSERT_EQ(s["imu_only"].size(), 2u);
  EXPECT_NEAR(s["imu_only"][0][0].get<double>(), 0.05, 1e-9);
  EXPECT_NEAR(s["imu_only"][0][1].get<double>(), 0.07, 1e-9);
  EXPECT_NEAR(s["imu_only"][1][0].get<double>(), 0.09, 1e-9);
  EXPECT_EQ(s["bootstraps"], 1);
  EXPECT_EQ(s["reinitialisations"], 1);
  EXPECT_EQ(s["bootstrap_failures"]["ticks"], 1);
  EXPECT_EQ(s["bootstrap_failures"]["last_reason"], "too few points");
  EXPECT_NEAR(s["first_bootstrap_s"].get<double>(), 0.01, 1e-9);
  EXPECT_EQ(s["mapping_cycles"], 1);
  EXPECT_EQ(s["mapping_cycles_skipped"], 1);
  EXPECT_EQ(s["dropped_events"], 15);
}

TEST(TickCounts, MappingOnGroundTruthCountsCyclesAndNoTickNoFirstMap) {
  TickCounts counts(0);
  counts.AddMappingCycle(/*bootstrap=*/true);
  counts.AddMappingCycle(/*bootstrap=*/false);
  nlohmann::json s;
  counts.AddTo(&s, std::nullopt);
  EXPECT_EQ(s["mapping_cycles"], 2);
  EXPECT_EQ(s["bootstraps"], 1);
  EXPECT_TRUE(s["first_bootstrap_s"].is_null());
  EXPECT_TRUE(s["imu_only"].empty());
}

}  // namespace
}  // namespace aavio::recording
