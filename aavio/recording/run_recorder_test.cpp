// The run recorder on a simulated mini sequence: what it writes in each mode, and that the depth
// it scores as the maps are made is what scoring the written files gives.
#include "aavio/recording/run_recorder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/ply.hpp"
#include "tests/preset_config.hpp"
#include "tests/simulated_sequence.hpp"

namespace aavio::recording {
namespace {

namespace fs = std::filesystem;

using Mini = aavio::testing::SimulatedSequence;

const Mini& MiniSequence() {
  return aavio::testing::MiniTwin(1.5, 2, kNsPerMs);
}

pipeline::OdometryConfig Config() {
  return aavio::testing::MiniConfig(MiniSequence().rig);
}

// A FIFO of 5 cycles confirms a map every cycle once full: many maps in 1.5 s (the indoor preset's
// const_points FIFO is not full again after the bootstrap on this small sensor).
pipeline::OdometryConfig ConfigConfirmingEveryCycle() {
  pipeline::OdometryConfig config = Config();
  config.mapping.fusion.strategy = mapping::FusionStrategy::kConstFrames;
  config.mapping.fusion.max_frames = 5;
  return config;
}

nlohmann::json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  nlohmann::json j;
  in >> j;
  return j;
}

TEST(RunRecorder, OdometryRunWritesEverythingAndScoresDepthAsTheFilesScore) {
  const Mini& m = MiniSequence();
  ASSERT_TRUE(m.rig.has_value());
  const fs::path out = aavio::testing::ScratchDir() / "run";
  // An earlier run in the folder is refused; replaced (none of its files left) with overwrite.
  fs::create_directories(out / "depth");
  aavio::testing::WriteFile(out / "depth" / "disparity_999999.png", "stale");
  aavio::testing::WriteFile(out / "stamped_traj_estimate.txt", "stale");

  const pipeline::OdometryConfig config = Config();
  RunRecorderOptions options;
  options.out_dir = out.string();
  options.sequence = m.description.origin;
  options.config_yaml = "# test\n";
  options.begin_ns = m.start_ns;
  EXPECT_FALSE(RunRecorder::Open(options, *m.rig, config).ok());
  EXPECT_TRUE(fs::exists(out / "stamped_traj_estimate.txt"));
  options.overwrite = true;
  Expected<std::unique_ptr<RunRecorder>> recorder = RunRecorder::Open(options, *m.rig, config);
  ASSERT_TRUE(recorder.ok()) << recorder.status().message();
  EXPECT_FALSE(fs::exists(out / "stamped_traj_estimate.txt"));
  EXPECT_FALSE(fs::exists(out / "depth" / "disparity_999999.png"));
  Expected<RunGroundTruth> truth = RunGroundTruth::Of(m.description, *m.rig);
  ASSERT_TRUE(truth.ok()) << truth.status().message();
  ASSERT_TRUE((*recorder)->SetGroundTruth(*truth, m.truth).ok());

  pipeline::Odometry odometry(*m.rig, config, m.start_ns);
  Status tick_status = Status::Ok();
  odometry.on_tick = [&](const pipeline::OdometryTick& t) {
    if (tick_status.ok()) tick_status = (*recorder)->AddTick(t);
  };
  TimeNs end = m.start_ns;
  for (const io::SensorPacket& p : m.packets) {
    ASSERT_TRUE(odometry.Process(p.left, p.right, p.imu, p.t_end_ns).ok());
    (*recorder)->AddPacket(p.left.size() + p.right.size(), 0.1);
    end = p.t_end_ns;
  }
  ASSERT_TRUE(odometry.Finish().ok());
  ASSERT_TRUE(tick_status.ok()) << tick_status.message();
  Expected<RunRecord> record = (*recorder)->Finish(false, end, {{"extra_key", 7}});
  ASSERT_TRUE(record.ok()) << record.status().message();

  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["extra_key"], 7);
  EXPECT_EQ(summary["sequence"], m.description.origin);
  EXPECT_EQ(summary["poses"], odometry.ticks());
  EXPECT_GT(summary["mapping_cycles"].get<int>(), 5);
  ASSERT_TRUE(summary.contains("accuracy"));
  EXPECT_LT(summary["accuracy"]["ate_rmse_m"].get<double>(), 0.1);
  Expected<std::vector<geometry::StampedPose>> written =
      io::ReadTumTrajectory((out / "stamped_traj_estimate.txt").string());
  ASSERT_TRUE(written.ok());
  EXPECT_EQ(written->size(), static_cast<std::size_t>(odometry.ticks()));
  std::ifstream csv(out / "timings.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);)
    ++lines;
  EXPECT_EQ(lines, static_cast<std::size_t>(odometry.ticks()) + 1);
  EXPECT_GE(summary["depth_maps"].get<int>(), 1);
  EXPECT_EQ(summary["depth_maps_written"].get<int>(),
            static_cast<int>(io::ReadGtDepthIndex((out / "depth").string())->size()));

  // map.ply holds the global cloud, in the layout the reader takes back.
  Expected<ColouredCloud> cloud = ReadPly((out / "map.ply").string());
  ASSERT_TRUE(cloud.ok()) << cloud.status().message();
  EXPECT_EQ(cloud->points.size(), summary["map_points_global"].get<std::size_t>());
  EXPECT_GT(cloud->points.size(), 100u);
  EXPECT_FALSE(fs::exists(out / "map.ply.part"));  // streamed there while the run went

  // Depth scored in memory equals depth scored from the written depth/.
  ASSERT_TRUE(record->depth.has_value());
  Expected<eval::DepthErrorAccumulator> from_files =
      EvaluateRunDepth((out / "depth").string(), *truth, m.truth);
  ASSERT_TRUE(from_files.ok()) << from_files.status().message();
  const eval::DepthErrorSummary files = from_files->Summary();
  EXPECT_EQ(record->depth->frames, files.frames);
  EXPECT_EQ(record->depth->points, files.points);
  EXPECT_DOUBLE_EQ(record->depth->relative, files.relative);
  EXPECT_DOUBLE_EQ(record->depth->completeness, files.completeness);
}

TEST(RunRecorder, MappingOnGroundTruthPosesScoresEveryMapAndItsCeiling) {
  const Mini& m = MiniSequence();
  ASSERT_TRUE(m.rig.has_value());
  const fs::path out = aavio::testing::ScratchDir() / "gt_poses";
  const pipeline::OdometryConfig config = ConfigConfirmingEveryCycle();
  RunRecorderOptions options;
  options.out_dir = out.string();
  options.mode = "mapping_only_gt_poses";
  options.sequence = m.description.origin;
  options.begin_ns = m.start_ns;
  Expected<std::unique_ptr<RunRecorder>> recorder = RunRecorder::Open(options, *m.rig, config);
  ASSERT_TRUE(recorder.ok());
  Expected<RunGroundTruth> truth = RunGroundTruth::Of(m.description, *m.rig);
  ASSERT_TRUE(truth.ok());
  ASSERT_TRUE((*recorder)->SetGroundTruth(*truth, m.truth).ok());
  geometry::PoseBuffer poses(0);
  for (const geometry::StampedPose& p : m.truth)
    ASSERT_TRUE(poses.Insert(p.t_ns, p.T_world_body).ok());
  pipeline::MappingFrontEnd front_end(*m.rig, config, poses, m.start_ns);
  Status status = Status::Ok();
  int cycles = 0;
  front_end.on_tick = [&](TimeNs t_ns, const events::RepresentationTimings& t) {
    (*recorder)->AddMappingTick(t_ns, t);
  };
  front_end.on_cycle = [&](const pipeline::MappingCycle& c) {
    ++cycles;
    if (status.ok()) status = (*recorder)->AddMappingCycle(c);
  };
  for (const io::SensorPacket& p : m.packets)
    ASSERT_TRUE(front_end.Process(p.left, p.right, p.t_end_ns).ok());
  ASSERT_TRUE(status.ok()) << status.message();
  Expected<RunRecord> record = (*recorder)->Finish(false, m.packets.back().t_end_ns);
  ASSERT_TRUE(record.ok()) << record.status().message();
  EXPECT_FALSE(record->accuracy.has_value());  // no trajectory of its own
  EXPECT_FALSE(fs::exists(out / "stamped_traj_estimate.txt"));
  ASSERT_TRUE(record->depth.has_value());
  ASSERT_TRUE(record->sample_ceiling.has_value());
  // Every confirmed map is scored, not only those written to depth/.
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["mapping_cycles"].get<int>(), cycles);
  EXPECT_EQ(record->depth->frames, summary["depth_maps"].get<std::size_t>());
  // Five a second of them go to depth/ (every rate_hz / 5-th confirmed map).
  const int every = static_cast<int>(std::lround(config.mapping.rate_hz / 5.0));
  EXPECT_EQ(summary["depth_maps_written"].get<int>(),
            (summary["depth_maps"].get<int>() + every - 1) / every);
  EXPECT_GT(record->depth->frames, summary["depth_maps_written"].get<std::size_t>());
  EXPECT_LT(record->depth->relative, 0.15);
  EXPECT_GT(record->sample_ceiling->completeness, 0.2);
  EXPECT_TRUE(summary["depth"].contains("sample_ceiling"));
  EXPECT_TRUE(fs::exists(out / "map.ply"));
}

}  // namespace
}  // namespace aavio::recording
