#include "aavio/pipeline/scene_depth_probe.hpp"

#include <gtest/gtest.h>

#include "aavio/sim/event_simulation.hpp"
#include "aavio/sim/world.hpp"

namespace aavio::pipeline {
namespace {

// The probe on a simulated rig: the median depth it measures after `seconds` of events.
std::optional<SceneDepth> Probe(const std::string& preset, double baseline_m, double seconds,
                                double rest_s = 0.0) {
  sim::SimulationRequest request;
  request.preset = preset;
  request.duration_s = 2.0;
  request.sensor = "ideal";
  request.baseline_m = baseline_m;
  request.rest_at_start_s = rest_s;
  Expected<sim::SimulationWorld> world = sim::BuildSimulationWorld(request);
  EXPECT_TRUE(world.ok()) << world.status().message();
  sim::StereoEventSimulation simulation(*world, 7);
  const TimeNs t0 = world->spline.t_begin_ns();
  simulation.Start(t0);
  SceneDepthProbe probe(world->calibration_rig, t0);
  const TimeNs until = t0 + SecondsToNs(seconds);
  while (simulation.time_ns() < until) {
    std::vector<events::Event> left, right;
    simulation.Step(until, &left, &right);
    EXPECT_TRUE(probe.AddEvents(events::Camera::kLeft, left).ok());
    EXPECT_TRUE(probe.AddEvents(events::Camera::kRight, right).ok());
  }
  Expected<std::optional<SceneDepth>> depth = probe.Measure(until);
  EXPECT_TRUE(depth.ok()) << depth.status().message();
  return depth.ok() ? *depth : std::nullopt;
}

TEST(SceneDepthProbe, MeasuresHowFarTheSceneIs) {
  // The room's walls stand 2.5-4.5 m from where the camera starts; the street's houses further.
  const std::optional<SceneDepth> room = Probe("mini", 0.15, 0.3);
  ASSERT_TRUE(room.has_value());
  EXPECT_GT(static_cast<int>(room->depths_m.size()), 100);
  EXPECT_GT(room->median_m(), 1.5);
  EXPECT_LT(room->median_m(), 4.5);
  EXPECT_DOUBLE_EQ(room->at_s, 0.3);
  // A 60 cm rig in the same room measures it as near (its search reaches 1 m).
  const std::optional<SceneDepth> wide = Probe("mini", 0.6, 0.3);
  ASSERT_TRUE(wide.has_value());
  EXPECT_GT(wide->median_m(), 1.5);
  EXPECT_LT(wide->median_m(), 4.5);
}

TEST(SceneDepthProbe, AStillCameraShowsNothingToMeasure) {
  // Standing still for its first second, the camera sees no edges (the ideal sensor: no noise).
  EXPECT_FALSE(Probe("mini", 0.15, 0.3, /*rest_s=*/1.0).has_value());
}

}  // namespace
}  // namespace aavio::pipeline
