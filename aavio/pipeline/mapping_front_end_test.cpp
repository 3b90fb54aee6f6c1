// Mapping alone as a library: MappingFrontEnd on the ground-truth poses of a simulated mini
// sequence (typical sensor) fed from memory — the bootstrap, the cycles, the gaps where no pose is
// known, and the same maps bit for bit at one and two threads.
#include "aavio/pipeline/mapping_front_end.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "tests/preset_config.hpp"
#include "tests/simulated_sequence.hpp"

namespace aavio::pipeline {
namespace {

const aavio::testing::SimulatedSequence& Mini() {
  return aavio::testing::MiniTwin(1.5, 4);
}

struct MappingRun {
  std::vector<MappingCycle> cycles;
  std::int64_t ticks = 0;
};

/// Every mapping cycle, with the ground-truth poses from `from_s` on only (none before).
MappingRun RunMini(const OdometryConfig& config, double poses_from_s = 0.0) {
  const aavio::testing::SimulatedSequence& r = Mini();
  MappingRun run;
  if (!r.rig || r.packets.empty() || r.truth.empty()) {
    ADD_FAILURE() << "the mini sequence could not be simulated or read";
    return run;
  }
  geometry::PoseBuffer poses(0);
  for (const geometry::StampedPose& p : r.truth) {
    if (p.t_ns < r.start_ns + SecondsToNs(poses_from_s)) continue;
    EXPECT_TRUE(poses.Insert(p.t_ns, p.T_world_body).ok());
  }
  MappingFrontEnd front_end(*r.rig, config, poses, r.start_ns);
  front_end.on_cycle = [&](const MappingCycle& c) { run.cycles.push_back(c); };
  std::int64_t ticks = 0;
  front_end.on_tick = [&](TimeNs, const events::RepresentationTimings&) { ++ticks; };
  for (const io::SensorPacket& p : r.packets) {
    const Status s = front_end.Process(p.left, p.right, p.t_end_ns);
    EXPECT_TRUE(s.ok()) << s.message();
  }
  EXPECT_EQ(ticks, front_end.ticks());
  run.ticks = front_end.ticks();
  return run;
}

TEST(MappingFrontEnd, BootstrapsAtTheFirstCycleThenMapsEveryCycle) {
  const OdometryConfig config = aavio::testing::PresetConfig("indoor", Mini().rig);
  const MappingRun run = RunMini(config);
  ASSERT_FALSE(run.cycles.empty());
  const double cycles_per_s = config.mapping.rate_hz;
  // A cycle every 1/rate_hz s of the 1.5 s, the first a bootstrap (the mini scene has texture
  // from the start), no second one: mapping on known poses never loses its map.
  EXPECT_NEAR(static_cast<double>(run.cycles.size()), 1.5 * cycles_per_s, 1.0);
  EXPECT_TRUE(run.cycles.front().bootstrap);
  ASSERT_TRUE(run.cycles.front().map != nullptr);
  EXPECT_GE(static_cast<int>(run.cycles.front().map->points.size()),
            config.mapping.bootstrap.min_points);
  int with_partner = 0;
  for (std::size_t i = 1; i < run.cycles.size(); ++i) {
    const MappingCycle& c = run.cycles[i];
    EXPECT_FALSE(c.bootstrap) << i;
    EXPECT_GT(c.report.samples, 0) << i;
    with_partner += c.report.has_partner;
    EXPECT_GT(c.t_ns, run.cycles[i - 1].t_ns);
    ASSERT_TRUE(c.observation != nullptr);
    if (c.map) {
      // Published maps sit at their cycle's (ground-truth) pose, and their points are finite.
      EXPECT_EQ(c.map->t_ns, c.t_ns);
      for (const Eigen::Vector3d& p : c.map->points_world)
        ASSERT_TRUE(p.allFinite());
    }
  }
  // Temporal stereo finds partners once the camera has moved min_translation_m.
  EXPECT_GT(with_partner, static_cast<int>(run.cycles.size()) / 2);
}

TEST(MappingFrontEnd, MapsNothingWhereNoPoseIsKnownAndBootstrapsOnceOneIs) {
  const OdometryConfig config = aavio::testing::PresetConfig("indoor", Mini().rig);
  const MappingRun run = RunMini(config, /*poses_from_s=*/0.5);
  ASSERT_FALSE(run.cycles.empty());
  const TimeNs poses_from = Mini().start_ns + SecondsToNs(0.5);
  // Ticks run all along (the representations are built), cycles only with a pose.
  EXPECT_NEAR(static_cast<double>(run.ticks), 1.5 * config.time_surface.rate_hz, 2.0);
  EXPECT_GE(run.cycles.front().t_ns, poses_from);
  EXPECT_TRUE(run.cycles.front().bootstrap);
  EXPECT_LE(run.cycles.front().t_ns - poses_from, SecondsToNs(2.0 / config.mapping.rate_hz));
}

TEST(MappingFrontEnd, TheSameMapsBitForBitAtOneAndTwoThreads) {
  const OdometryConfig config = aavio::testing::PresetConfig("indoor", Mini().rig);
  MappingRun one, two;
  {
    tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 1);
    one = RunMini(config);
  }
  {
    tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 2);
    two = RunMini(config);
  }
  ASSERT_EQ(one.cycles.size(), two.cycles.size());
  for (std::size_t i = 0; i < one.cycles.size(); ++i) {
    const MappingCycle &a = one.cycles[i], &b = two.cycles[i];
    ASSERT_EQ(a.map != nullptr, b.map != nullptr) << i;
    EXPECT_EQ(a.report.static_matches, b.report.static_matches) << i;
    EXPECT_EQ(a.report.temporal_matches, b.report.temporal_matches) << i;
    if (!a.map) continue;
    ASSERT_EQ(a.map->points.size(), b.map->points.size()) << i;
    for (std::size_t k = 0; k < a.map->points.size(); ++k) {
      // Bit for bit: == on doubles, not a tolerance.
      ASSERT_EQ(a.map->points[k].rho, b.map->points[k].rho) << i << " " << k;
      ASSERT_EQ(a.map->points[k].u, b.map->points[k].u) << i << " " << k;
    }
  }
}

}  // namespace
}  // namespace aavio::pipeline
