#include "aavio/sim/world.hpp"

#include <gtest/gtest.h>

namespace aavio::sim {
namespace {

// The mini preset for 3 s with the ideal sensor.
SimulationRequest MiniRequest() {
  SimulationRequest request;
  request.preset = "mini";
  request.duration_s = 3.0;
  request.sensor = "ideal";
  return request;
}

SimulationWorld WorldOf(const SimulationRequest& request) {
  Expected<SimulationWorld> world = BuildSimulationWorld(request);
  EXPECT_TRUE(world.ok()) << world.status().message();
  return std::move(*world);
}

SimulationWorld World(std::vector<Disturbance> disturbances) {
  SimulationRequest request = MiniRequest();
  request.disturbances = std::move(disturbances);
  return WorldOf(request);
}

TimeNs At(const SimulationWorld& w, double t_s) {
  return w.spline.t_begin_ns() + SecondsToNs(t_s);
}

TEST(SimulationWorld, SpeedPlaysTheSamePathFasterOrSlower) {
  const SimulationWorld plain = World({});
  for (double speed : {0.5, 2.0}) {
    SCOPED_TRACE(speed);
    SimulationRequest request = MiniRequest();
    request.speed = speed;
    const SimulationWorld w = WorldOf(request);
    // As long in data time; at t it is where the plain motion is at speed·t, moving speed× as fast.
    EXPECT_NEAR(NsToSeconds(w.spline.t_end_ns() - w.spline.t_begin_ns()), 3.0, 0.01);
    for (double t : {0.3, 0.6, 1.2}) {
      EXPECT_LT((w.spline.Position(At(w, t)) - plain.spline.Position(At(plain, speed * t))).norm(),
                1e-3)
          << t;
      EXPECT_NEAR(w.spline.LinearVelocity(At(w, t)).norm(),
                  speed * plain.spline.LinearVelocity(At(plain, speed * t)).norm(), 1e-2)
          << t;
    }
  }
  SimulationRequest absurd;
  absurd.speed = 0.0;
  EXPECT_NE(absurd.Validate().message().find("speed"), std::string::npos);
}

TEST(SimulationWorld, APresetsSensorTakesAnotherScenesAndMotion) {
  SimulationRequest request = MiniRequest();
  request.duration_s = 1.0;
  request.scene = "planes";
  request.motion = "sinusoid";
  const SimulationWorld w = WorldOf(request);
  EXPECT_EQ(w.scene.quads().size(), 4u);                        // the planes
  EXPECT_EQ(w.rig.width(), 160);                                // the mini preset's sensor
  EXPECT_GT(w.spline.LinearVelocity(At(w, 0.0)).norm(), 0.05);  // the sinusoid moves at once
  request.scene = "moon";
  EXPECT_NE(BuildSimulationWorld(request).status().message().find("scene = 'moon' is not a scene"),
            std::string::npos);
  request.scene = "";
  request.motion = "sinusoid";
  request.trajectory = "path.txt";
  EXPECT_NE(BuildSimulationWorld(request).status().message().find("cannot both be given"),
            std::string::npos);
}

TEST(SimulationWorld, ABaselineReplacesThePresetsAndTheCalibrationFollows) {
  SimulationRequest request;
  request.preset = "mini";
  request.duration_s = 0.5;
  request.baseline_m = 0.45;
  Expected<SimulationWorld> w = BuildSimulationWorld(request);
  ASSERT_TRUE(w.ok()) << w.status().message();
  EXPECT_NEAR(w->rig.baseline_m(), 0.45, 1e-9);
  // The typical sensor's calibration error is a few tenths of a millimetre, not the old baseline.
  EXPECT_NEAR(w->calibration_rig.baseline_m(), 0.45, 0.01);
  request.baseline_m = 3.0;
  EXPECT_NE(request.Validate().message().find("baseline_m"), std::string::npos);
}

TEST(SimulationWorld, AStopBrakesStandsStillAndDrivesOn) {
  const SimulationWorld plain = World({});
  // Stop over 1–2 s: braking 1–1.25 s, standing 1.25–1.75 s, starting 1.75–2 s.
  const SimulationWorld stop = World({{Disturbance::Kind::kStop, 1.0, 1.0}});
  // Same length of data, the same motion before the stretch.
  EXPECT_NEAR(NsToSeconds(stop.spline.t_end_ns() - stop.spline.t_begin_ns()),
              NsToSeconds(plain.spline.t_end_ns() - plain.spline.t_begin_ns()), 0.01);
  for (double t : {0.2, 0.5, 0.8}) {
    EXPECT_LT((stop.spline.Position(At(stop, t)) - plain.spline.Position(At(plain, t))).norm(),
              1e-3)
        << t;
  }
  const double cruise = plain.spline.LinearVelocity(At(plain, 1.0)).norm();
  ASSERT_GT(cruise, 0.1);
  // Standing: no speed, no turn, one place.
  const Eigen::Vector3d parked = stop.spline.Position(At(stop, 1.3));
  for (double t = 1.3; t <= 1.7; t += 0.05) {
    EXPECT_LT(stop.spline.LinearVelocity(At(stop, t)).norm(), 0.02 * cruise) << t;
    EXPECT_LT(stop.spline.AngularVelocity(At(stop, t)).norm(), 0.02) << t;
    EXPECT_LT((stop.spline.Position(At(stop, t)) - parked).norm(), 1e-3) << t;
  }
  // Braking slows it down smoothly: half the speed halfway through the ramp, give or take.
  const double braking = stop.spline.LinearVelocity(At(stop, 1.125)).norm();
  const double plain_there = plain.spline.LinearVelocity(At(plain, 1.0625)).norm();
  EXPECT_GT(braking, 0.2 * plain_there);
  EXPECT_LT(braking, 0.8 * plain_there);
  // And it drives on: 1 s after the stretch it moves as the plain motion 0.25 s later in its
  // path (the stretch covered a quarter of its length in motion).
  EXPECT_NEAR(stop.spline.LinearVelocity(At(stop, 2.5)).norm(),
              plain.spline.LinearVelocity(At(plain, 1.75)).norm(), 0.05 * cruise);
}

TEST(SimulationWorld, ARestAtTheStartStandsStillThenSpeedsUpIntoTheMotion) {
  const SimulationWorld plain = World({});
  SimulationRequest request = MiniRequest();
  request.rest_at_start_s = 1.0;
  const SimulationWorld rest = WorldOf(request);
  // As long as asked; standing where the plain motion starts for the first second.
  EXPECT_NEAR(NsToSeconds(rest.spline.t_end_ns() - rest.spline.t_begin_ns()), 3.0, 0.01);
  const Eigen::Vector3d start = plain.spline.Position(At(plain, 0.0));
  for (double t = 0.0; t <= 0.95; t += 0.05) {
    EXPECT_LT((rest.spline.Position(At(rest, t)) - start).norm(), 1e-3) << t;
    EXPECT_LT(rest.spline.AngularVelocity(At(rest, t)).norm(), 0.02) << t;
  }
  // Up to speed after half a second more: then it moves as the plain motion a quarter second
  // into its path (the ramp covered a quarter of a second of it).
  const double cruise = plain.spline.LinearVelocity(At(plain, 1.0)).norm();
  ASSERT_GT(cruise, 0.1);
  EXPECT_GT(rest.spline.LinearVelocity(At(rest, 1.25)).norm(), 0.05 * cruise);
  EXPECT_LT((rest.spline.Position(At(rest, 2.0)) - plain.spline.Position(At(plain, 0.75))).norm(),
            1e-3);
  // A rest that leaves no time to move is refused.
  request.rest_at_start_s = 2.5;
  EXPECT_NE(request.Validate().message().find("rest_at_start_s = 2.5 s leaves the camera no time"),
            std::string::npos)
      << request.Validate().message();
}

TEST(SimulationWorld, TextureContrastScalesTheScenesPatternsOnly) {
  const SimulationWorld plain = World({});
  SimulationRequest request = MiniRequest();
  request.texture_contrast = 0.5;
  const SimulationWorld faint = WorldOf(request);
  ASSERT_EQ(faint.scene.quads().size(), plain.scene.quads().size());
  for (std::size_t i = 0; i < plain.scene.quads().size(); ++i) {
    const Quad &a = plain.scene.quads()[i], &b = faint.scene.quads()[i];
    EXPECT_DOUBLE_EQ(b.texture.contrast, 0.5 * a.texture.contrast) << i;
    EXPECT_EQ(b.texture.mean, a.texture.mean) << i;
    EXPECT_EQ(b.origin, a.origin) << i;
  }
  request.texture_contrast = 5.0;
  EXPECT_NE(request.Validate().message().find("texture_contrast"), std::string::npos);
}

TEST(SimulationWorld, AStopPastTheEndIsAClearError) {
  SimulationRequest request;
  request.preset = "mini";
  request.duration_s = 1.0;
  request.disturbances = {{Disturbance::Kind::kStop, 0.5, 4.0}};
  const Status status = BuildSimulationWorld(request).status();
  EXPECT_NE(status.message().find("stop from 0.5 s for 4 s ends after the sequence (1 s)"),
            std::string::npos)
      << status.message();
}

TEST(SimulationWorld, AStretchAfterTheEndIsAClearError) {
  for (const Disturbance::Kind kind :
       {Disturbance::Kind::kDark, Disturbance::Kind::kRightOff, Disturbance::Kind::kFastMotion}) {
    SimulationRequest request;
    request.preset = "mini";
    request.duration_s = 1.0;
    request.disturbances = {{kind, 5.0, 1.0, 4.0}};
    EXPECT_NE(request.Validate().message().find("a stretch from 5 s starts after the sequence "
                                                "ends (1 s) and would change nothing"),
              std::string::npos)
        << request.Validate().message();
    request.disturbances = {{kind, 0.9, 1.0, 4.0}};  // starts within it: fine
    EXPECT_TRUE(request.Validate().ok()) << request.Validate().message();
  }
}

TEST(SimulationWorld, DarkAndCameraOffStretchesLeaveTheMotionAlone) {
  const SimulationWorld plain = World({});
  const SimulationWorld dark =
      World({{Disturbance::Kind::kDark, 1.0, 0.5}, {Disturbance::Kind::kRightOff, 2.0, 0.5}});
  for (double t : {0.5, 1.2, 2.2, 2.9})
    EXPECT_EQ(dark.spline.Position(At(dark, t)), plain.spline.Position(At(plain, t))) << t;
}

}  // namespace
}  // namespace aavio::sim
