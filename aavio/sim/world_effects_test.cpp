#include "aavio/sim/world_effects.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "aavio/sim/event_generator.hpp"
#include "aavio/sim/renderer.hpp"

namespace aavio::sim {
namespace {

constexpr double kHalfFov = 0.54;  // atan(120 / 200)

geometry::CameraModel Camera() {
  return *geometry::CameraModel::Create({240, 180, 200.0, 200.0, 119.5, 89.5});
}

/// A textured wall 4 m ahead and a floor 1.4 m below a camera that looks along +z (y down).
Scene Room() {
  Scene scene;
  Texture wall;
  wall.pattern = Pattern::kBlobs;
  wall.seed = 3;
  scene.AddQuad({{-8, -4, 4}, {16, 0, 0}, {0, 6, 0}, wall});
  scene.AddQuad({{-8, 1.4, -2}, {16, 0, 0}, {0, 0, 6}, Texture{}});
  scene.Build();
  return scene;
}

/// A camera standing still for `seconds`, or driving along +z at `speed_mps`.
WorldEffectPlacement StillCamera(double seconds, double speed_mps = 0.0) {
  WorldEffectPlacement p;
  for (TimeNs t = 0; t <= SecondsToNs(seconds); t += 10'000'000)
    p.camera_path.push_back({t, {Eigen::Matrix3d::Identity(), {0, 0, speed_mps * NsToSeconds(t)}}});
  p.gravity_world = {0, 9.81, 0};
  p.half_fov_rad = kHalfFov;
  p.seed = 4;
  return p;
}

TEST(WorldEffects, NamesAreCheckedAndNoneLeavesTheSceneAlone) {
  EXPECT_TRUE(CheckWorldEffectNames({"flicker", "moving_objects"}).ok());
  const Status unknown = CheckWorldEffectNames({"rain"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.message().find("flicker, moving_objects"), std::string::npos);
  Scene scene = Room();
  const WorldEffectsAdded added = AddWorldEffects({}, StillCamera(2.0), &scene);
  EXPECT_EQ(scene.quads().size(), 2u);
  EXPECT_EQ(added.Describe(), "none");
}

TEST(WorldEffects, FlickeringLightsSitInViewAndFireAtTheMainsRate) {
  Scene scene = Room();
  const WorldEffectsAdded added = AddWorldEffects({"flicker"}, StillCamera(2.0), &scene);
  EXPECT_EQ(added.lights, 4);  // two a second
  EXPECT_TRUE(added.flicker_hz == 100.0 || added.flicker_hz == 120.0);
  EXPECT_EQ(scene.quads().size(), 6u);

  // A still camera: events come only from the lamps, at each pixel some per period.
  const Renderer renderer(Camera());
  EventCameraConfig ideal;
  ideal.threshold_sigma = 0.0;
  ideal.noise_rate_hz = 0.0;
  EventGenerator generator(240, 180, ideal, 1);
  RenderedImage image;
  renderer.Render(scene, {}, 0, &image);
  generator.Reset(image.intensity, 0);
  const TimeNs step = SecondsToNs(1.0 / (12.0 * added.flicker_hz));
  const int periods = 10;
  std::vector<events::Event> events;
  for (TimeNs t = step; t <= periods * 12 * step; t += step) {
    renderer.Render(scene, {}, t, &image);
    generator.Step(image.intensity, t, &events);
  }
  ASSERT_FALSE(events.empty());
  // Lamp pixels: where the radiance differs between two phases half a period apart.
  RenderedImage a, b;
  renderer.Render(scene, {}, 0, &a);
  renderer.Render(scene, {}, SecondsToNs(0.5 / added.flicker_hz), &b);
  auto is_lamp = [&](std::size_t i) {
    return std::abs(std::log(a.intensity[i] / b.intensity[i])) > 1e-3f;
  };
  int lamp_pixels = 0;
  for (std::size_t i = 0; i < a.intensity.size(); ++i)
    lamp_pixels += is_lamp(i) ? 1 : 0;
  EXPECT_GT(lamp_pixels, 100);
  std::size_t on_lamp = 0;
  for (const events::Event& e : events) {
    const std::size_t i = static_cast<std::size_t>(e.y) * 240 + e.x;
    on_lamp += is_lamp(i) ? 1 : 0;
  }
  // Every event is a lamp's. A modulation depth m swings the log radiance by ln(1 / (1 − m)):
  // 0.36 at m = 0.3 (one event each way per period at a 0.25 threshold), 3.0 at m = 0.95
  // (12 each way).
  EXPECT_EQ(on_lamp, events.size());
  const double per_period = static_cast<double>(events.size()) / lamp_pixels / periods;
  EXPECT_GT(per_period, 2.0);
  EXPECT_LT(per_period, 24.0);
}

TEST(WorldEffects, PeopleWalkAcrossTheViewInFrontOfTheScene) {
  Scene scene = Room();
  const WorldEffectsAdded added = AddWorldEffects({"moving_objects"}, StillCamera(6.0), &scene);
  ASSERT_EQ(added.moving_objects, 2);  // one every ~3 s
  for (std::size_t q = 2; q < scene.quads().size(); ++q) {
    const double speed = scene.quads()[q].velocity_mps.norm();
    EXPECT_GE(speed, 1.0);
    EXPECT_LE(speed, 1.6);
    EXPECT_NEAR(scene.quads()[q].velocity_mps.y(), 0.0, 1e-9);  // level
  }
  // At each crossing (1.5 s and 4.5 s) someone stands in the middle of the view, nearer than
  // the wall and at least a quarter of the image wide; at the start, nobody is.
  const Renderer renderer(Camera());
  RenderedImage image;
  auto covered = [&](double t_s) {
    renderer.Render(scene, {}, SecondsToNs(t_s), &image);
    int columns = 0;
    for (int x = 0; x < 240; ++x)
      columns += image.depth_m[90 * 240 + x] < 3.0f ? 1 : 0;
    return columns / 240.0;
  };
  EXPECT_GT(covered(1.5), 0.25);
  EXPECT_GT(covered(4.5), 0.25);
  EXPECT_EQ(covered(0.0), 0.0);
}

TEST(WorldEffects, StreetsGetOncomingCarsAndCrossingCyclists) {
  Scene scene = Room();
  WorldEffectPlacement placement = StillCamera(6.0, 10.0);
  placement.street = true;
  const WorldEffectsAdded added = AddWorldEffects({"moving_objects"}, placement, &scene);
  ASSERT_EQ(added.moving_objects, 2);
  const Eigen::Vector3d car = scene.quads()[2].velocity_mps;
  const Eigen::Vector3d cyclist = scene.quads().back().velocity_mps;
  EXPECT_LT(car.z(), -8.0);  // towards the camera
  EXPECT_NEAR(std::abs(cyclist.x()), cyclist.norm(), 1e-9);  // across the road
  EXPECT_GE(cyclist.norm(), 4.0);
  // The same seed makes the same world.
  Scene again = Room();
  AddWorldEffects({"moving_objects"}, placement, &again);
  ASSERT_EQ(again.quads().size(), scene.quads().size());
  EXPECT_EQ(again.quads().back().origin, scene.quads().back().origin);
}

}  // namespace
}  // namespace aavio::sim
