#include "aavio/sim/simulator.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "aavio/geometry/rectification.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/sim/event_generator.hpp"
#include "aavio/sim/motions.hpp"
#include "aavio/sim/presets.hpp"
#include "aavio/sim/renderer.hpp"
#include "tests/test_utils.hpp"

namespace aavio::sim {
namespace {

TEST(Simulator, WritesAReadableSequenceAndSameSeedGivesSameBytes) {
  const auto a = testing::ScratchDir(), b = testing::ScratchDir();
  for (const auto& dir : {a, b}) {
    SimulationRequest request;
    request.preset = "mini";
    request.duration_s = 0.25;
    request.out_dir = (dir / "seq").string();
    Expected<SimulationReport> report = Simulate(request);
    ASSERT_TRUE(report.ok()) << report.status().message();
    EXPECT_GT(report->events_left, 10000);
    EXPECT_GT(report->events_right, 10000);
    EXPECT_EQ(report->depth_maps, 6);  // 20 Hz over 0.25 s, both ends
  }
  for (const char* file :
       {"events/left/events.h5", "events/right/events.h5", "imu.txt", "groundtruth.txt",
        "depth/disparity_000003.png", "calibration/left.yaml"}) {
    const std::string bytes = testing::ReadAll(a / "seq" / file);
    EXPECT_FALSE(bytes.empty()) << file;
    EXPECT_EQ(bytes, testing::ReadAll(b / "seq" / file)) << file;
  }
  // The readers understand it: events in time order within the sensor, IMU, ground truth.
  Expected<io::SequenceDescription> d = io::DescribeSequence((a / "seq").string());
  ASSERT_TRUE(d.ok()) << d.status().message();
  auto reader = io::SequenceReader::Open(
      *d, {.packet_ns = 5 * kNsPerMs, .stream = {.width = 160, .height = 120}});
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  io::SensorPacket packet;
  std::size_t left = 0, imu = 0;
  while (*(*reader)->Next(&packet)) {
    left += packet.left.size();
    imu += packet.imu.size();
  }
  EXPECT_GT(left, 10000u);
  EXPECT_EQ(imu, 126u);  // 500 Hz
  EXPECT_EQ(io::ReadTumTrajectory((a / "seq" / "groundtruth.txt").string())->size(), 51u);
}

TEST(Simulator, EventRateGrowsWithSpeed) {
  // The same hand-held path, once at its own pace and once twice as fast.
  const auto dir = testing::ScratchDir();
  // Recordings live in z-up worlds: turn the built-in motion's y-down world into one.
  Eigen::Matrix3d R_zup_ydown;
  R_zup_ydown << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  std::vector<geometry::StampedPose> slow, fast;
  for (const auto& p : HandHeldMotion(1.0, 3)) {
    const geometry::RigidTransform T(R_zup_ydown * p.T_world_body.R,
                                     R_zup_ydown * p.T_world_body.t);
    slow.push_back({p.t_ns, T});
    fast.push_back({p.t_ns / 2, T});
  }
  ASSERT_TRUE(io::WriteTumTrajectory((dir / "slow.txt").string(), slow).ok());
  ASSERT_TRUE(io::WriteTumTrajectory((dir / "fast.txt").string(), fast).ok());
  double rate[2];
  for (int k = 0; k < 2; ++k) {
    SimulationRequest request;
    request.preset = "mini";
    request.trajectory = (dir / (k == 0 ? "slow.txt" : "fast.txt")).string();
    request.out_dir = (dir / (k == 0 ? "slow" : "fast")).string();
    Expected<SimulationReport> report = Simulate(request);
    ASSERT_TRUE(report.ok()) << report.status().message();
    rate[k] = report->mean_rate_ev_s;
  }
  EXPECT_GT(rate[1], 1.6 * rate[0]) << rate[0] << " vs " << rate[1];
}

// A small bright square at a known depth: its events in the left and right cameras, rectified
// with the rig's look-up tables, lie on the same row and at the disparity f·b/z (+ cx offset).
TEST(Simulator, PointAtKnownDepthGivesTheRigsRowAndDisparity) {
  const geometry::StereoRig rig = *GetSimulationPreset("mini")->rig();
  const geometry::StereoRectification rect = geometry::BuildStereoRectification(rig);
  const double depth = 1.5;
  Scene scene;
  Quad background{{-50, -50, 40}, {100, 0, 0}, {0, 100, 0}, {}};
  background.texture.contrast = 0.0;
  background.texture.mean = 0.1;
  Quad square{{-0.02, -0.02, depth}, {0.04, 0, 0}, {0, 0.04, 0}, {}};
  square.texture.contrast = 0.0;
  square.texture.mean = 0.9;
  scene.AddQuad(background);
  scene.AddQuad(square);
  scene.Build();
  EventCameraConfig config;
  config.noise_rate_hz = 0.0;
  config.threshold_sigma = 0.0;
  const Renderer renderers[2] = {Renderer(rig.left()), Renderer(rig.right())};
  EventGenerator generators[2] = {EventGenerator(rig.width(), rig.height(), config, 1),
                                  EventGenerator(rig.width(), rig.height(), config, 2)};
  const geometry::RigidTransform T_rect_left(rig.R_rect_left_left(), Eigen::Vector3d::Zero());
  // Pose of the raw cameras for the rectified-left pose T_world_rect: the square sits on the
  // rectified optical axis when the rectified camera is at the origin.
  auto pose = [&](int side, const geometry::RigidTransform& T_world_rect) {
    const geometry::RigidTransform T_world_left = T_world_rect * T_rect_left;
    return side == 0 ? T_world_left : T_world_left * rig.T_right_left().Inverse();
  };
  double sum_v[2] = {0, 0}, sum_u[2] = {0, 0};
  int count[2] = {0, 0};
  for (int side = 0; side < 2; ++side) {
    RenderedImage image;
    renderers[side].Render(scene, pose(side, {}), 0, &image);
    generators[side].Reset(image.intensity, 0);
    std::vector<events::Event> events;
    // A small vertical shake: the square's horizontal edges fire, staying at the same depth.
    for (int k = 1; k <= 40; ++k) {
      const double dy = 0.004 * std::sin(k * 0.3);
      renderers[side].Render(scene, pose(side, {Eigen::Matrix3d::Identity(), {0, dy, 0}}), 0,
                             &image);
      generators[side].Step(image.intensity, k * kNsPerMs, &events);
    }
    const geometry::RectificationMaps& maps = side == 0 ? rect.left : rect.right;
    for (const events::Event& e : events) {
      const Eigen::Vector2f r = maps.RectifyPixel(e.x, e.y);
      sum_u[side] += static_cast<double>(r.x());
      sum_v[side] += static_cast<double>(r.y());
      ++count[side];
    }
  }
  ASSERT_GT(count[0], 20);
  ASSERT_GT(count[1], 20);
  const double v_left = sum_v[0] / count[0], v_right = sum_v[1] / count[1];
  const double disparity = sum_u[0] / count[0] - sum_u[1] / count[1];
  EXPECT_NEAR(v_left, v_right, 0.3);   // same rectified row
  EXPECT_NEAR(v_left, rig.cy(), 2.5);  // on the optical axis (square ±1.4 px, plus the shake)
  EXPECT_NEAR(disparity, rig.DisparityAtDepth(depth), 0.3);  // f·b/z
}

// World effects add lamps and moving objects to the world and leave the rest as it was: the same
// motion, IMU and ground-truth path; lamps add events, a moving object shows in the depth maps.
TEST(Simulator, WorldEffectsChangeTheWorldNotTheMotion) {
  const std::vector<std::vector<std::string>> effects = {{}, {"flicker"}, {"moving_objects"}};
  std::vector<std::filesystem::path> dirs;
  std::vector<SimulationReport> reports;
  for (const auto& names : effects) {
    dirs.push_back(testing::ScratchDir() / "seq");
    SimulationRequest request;
    request.preset = "mini";
    request.duration_s = 0.25;
    request.out_dir = dirs.back().string();
    request.world_effects = names;
    Expected<SimulationReport> report = Simulate(request);
    ASSERT_TRUE(report.ok()) << report.status().message();
    reports.push_back(*report);
  }
  EXPECT_GT(reports[1].events_left, reports[0].events_left);
  EXPECT_NE(reports[1].world_effects.find("flickering lights at 1"), std::string::npos)
      << reports[1].world_effects;
  EXPECT_EQ(reports[2].world_effects, "1 moving objects");
  for (std::size_t k = 1; k < dirs.size(); ++k) {
    for (const char* file : {"imu.txt", "groundtruth.txt"}) {
      const std::string bytes = testing::ReadAll(dirs[0] / file);
      EXPECT_FALSE(bytes.empty()) << file;
      EXPECT_EQ(bytes, testing::ReadAll(dirs[k] / file)) << file;
    }
  }
  EXPECT_NE(testing::ReadAll(dirs[0] / "depth/disparity_000003.png"),
            testing::ReadAll(dirs[2] / "depth/disparity_000003.png"));
  SimulationRequest bad;
  bad.out_dir = (testing::ScratchDir() / "x").string();
  bad.world_effects = {"rain"};
  EXPECT_NE(Simulate(bad).status().message().find("unknown world effect 'rain'"),
            std::string::npos);
}

TEST(Simulator, BadRequestsGiveClearErrors) {
  SimulationRequest request;
  request.out_dir = (testing::ScratchDir() / "x").string();
  request.preset = "kitti";
  EXPECT_NE(Simulate(request).status().message().find("no simulation preset named 'kitti'"),
            std::string::npos);
  request.preset = "mini";
  request.format = "csv";
  EXPECT_NE(Simulate(request).status().message().find("format = 'csv' must be h5, bag or txt"),
            std::string::npos);
  request.format = "h5";
  request.duration_s = -1.0;
  EXPECT_NE(Simulate(request).status().message().find("duration_s = -1 must be in [0.001, 86400]"),
            std::string::npos)
      << Simulate(request).status().message();
  request.duration_s.reset();
  request.format = "h5";
  request.trajectory = "/nonexistent/path.txt";
  EXPECT_NE(Simulate(request).status().message().find("/nonexistent/path.txt"), std::string::npos);
}

}  // namespace
}  // namespace aavio::sim
