// The odometry as a library: bootstrap, tracking, recovery after a loss and determinism, on a
// simulated mini sequence (typical sensor) fed from memory.
#include "aavio/pipeline/odometry.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <optional>
#include <random>

#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/sim/simulator.hpp"
#include "tests/preset_config.hpp"
#include "tests/simulated_sequence.hpp"

namespace aavio::pipeline {
namespace {

const aavio::testing::SimulatedSequence& Mini() {
  return aavio::testing::MiniTwin(1.5, 3);
}

OdometryConfig RpgPreset() {
  return aavio::testing::MiniConfig(Mini().rig);
}

/// Every tick of the recording; the cameras see nothing in [blind_from_s, blind_to_s); the IMU's
/// stamps are `imu_late_ns` late (each packet gets the samples stamped before its end), and
/// `alter_imu` (if given) changes each sample.
std::vector<OdometryTick> RunMini(const OdometryConfig& config, double blind_from_s = -1.0,
                                  double blind_to_s = -1.0, TimeNs imu_late_ns = 0,
                                  const std::function<void(imu::ImuSample*)>& alter_imu = {},
                                  TimeNs shift_ns = 0) {
  const aavio::testing::SimulatedSequence& r = Mini();
  if (!r.rig || r.packets.empty()) {
    ADD_FAILURE() << "the mini sequence could not be simulated or read";
    return {};
  }
  std::vector<imu::ImuSample> imu;
  for (const io::SensorPacket& p : r.packets)
    for (imu::ImuSample s : p.imu) {
      s.t_ns += imu_late_ns + shift_ns;
      if (alter_imu) alter_imu(&s);
      imu.push_back(s);
    }
  Odometry odometry(*r.rig, config, r.start_ns + shift_ns);
  std::vector<OdometryTick> ticks;
  odometry.on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  const std::vector<events::Event> none;
  auto shifted = [shift_ns](std::vector<events::Event> events) {
    for (events::Event& e : events)
      e.t_ns += shift_ns;
    return events;
  };
  std::size_t next_imu = 0;
  for (const io::SensorPacket& p : r.packets) {
    const double t_s = NsToSeconds(p.t_begin_ns - r.start_ns);
    const bool blind = t_s >= blind_from_s && t_s < blind_to_s;
    const TimeNs t_end_ns = p.t_end_ns + shift_ns;
    const std::size_t first_imu = next_imu;
    while (next_imu < imu.size() && imu[next_imu].t_ns < t_end_ns)
      ++next_imu;
    const Status s = odometry.Process(
        blind ? none : shifted(p.left), blind ? none : shifted(p.right),
        std::span<const imu::ImuSample>(imu).subspan(first_imu, next_imu - first_imu), t_end_ns);
    EXPECT_TRUE(s.ok()) << s.message();
  }
  const Status s = odometry.Finish();
  EXPECT_TRUE(s.ok()) << s.message();
  return ticks;
}

bool Finite(const geometry::RigidTransform& T) {
  return T.R.allFinite() && T.t.allFinite();
}

TEST(Odometry, BootstrapsOnceThenTracks) {
  const std::vector<OdometryTick> ticks = RunMini(RpgPreset());
  ASSERT_GT(ticks.size(), 140u);
  int bootstraps = 0, ok = 0, maps = 0;
  std::size_t first_bootstrap = ticks.size();
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    const OdometryTick& t = ticks[i];
    ASSERT_TRUE(Finite(t.T_world_cam)) << "tick " << i;
    if (t.bootstrap) {
      ++bootstraps;
      first_bootstrap = std::min(first_bootstrap, i);
    }
    if (i < first_bootstrap) {
      EXPECT_EQ(t.status, tracking::TrackingStatus::kNoMap) << i;
    }
    ok += t.status == tracking::TrackingStatus::kOk;
    maps += t.map != nullptr;
    EXPECT_FALSE(t.reinitialised) << i;
  }
  EXPECT_EQ(bootstraps, 1);
  EXPECT_LT(first_bootstrap, 20u);  // within the first 0.2 s
  EXPECT_GT(ok, static_cast<int>(ticks.size()) * 8 / 10);
  EXPECT_GT(maps, 10);
  // The estimate follows the camera: the end position within 10 cm of the truth's (the world is
  // the first camera frame on both sides; mini moves about 40 cm in 1.5 s).
  ASSERT_FALSE(Mini().truth.empty());
  const Eigen::Vector3d end = ticks.back().T_world_cam.t;
  const geometry::StampedPose& truth_end = Mini().truth.back();
  const geometry::StampedPose& truth_start = Mini().truth.front();
  const Eigen::Vector3d truth_moved = truth_start.T_world_body.R.transpose() *
                                      (truth_end.T_world_body.t - truth_start.T_world_body.t);
  EXPECT_LT((end - truth_moved).norm(), 0.10)
      << end.transpose() << " vs " << truth_moved.transpose();
}

// Too few points for the first map: every tick says why and tries again; none tracks.
TEST(Odometry, SaysWhyTheBootstrapFailsAndRetriesEveryTick) {
  OdometryConfig config = RpgPreset();
  config.mapping.bootstrap.min_points = 1000000;
  config.mapping.bootstrap.min_coverage = 0.0;
  const std::vector<OdometryTick> ticks = RunMini(config);
  ASSERT_GT(ticks.size(), 100u);
  for (const OdometryTick& t : ticks) {
    EXPECT_FALSE(t.bootstrap);
    EXPECT_EQ(t.status, tracking::TrackingStatus::kNoMap);
    EXPECT_NE(t.bootstrap_failure.find("mapping.bootstrap.min_points = 1000000"), std::string::npos)
        << t.bootstrap_failure;
  }
  // With enough points the same ticks report no failure once the map stands.
  const std::vector<OdometryTick> normal = RunMini(RpgPreset());
  std::size_t failures = 0;
  for (const OdometryTick& t : normal)
    failures += !t.bootstrap_failure.empty();
  EXPECT_LT(failures, 20u);
}

TEST(Odometry, RecoversAfterScrambledEventsAtTheHeldPose) {
  const OdometryConfig config = RpgPreset();
  const std::vector<OdometryTick> ticks = RunMini(config, 0.6, 0.9);
  int lost = 0, reinitialised = 0, ok_after = 0;
  std::size_t reinit_tick = 0;
  geometry::RigidTransform last_ok;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    const OdometryTick& t = ticks[i];
    ASSERT_TRUE(Finite(t.T_world_cam)) << "tick " << i;
    lost += t.status == tracking::TrackingStatus::kLost;
    if (t.reinitialised && reinitialised++ == 0) {
      reinit_tick = i;
      // Mapping starts again where the camera was last tracked, never at the origin.
      EXPECT_LT((t.T_world_cam.t - last_ok.t).norm(), 0.05);
      EXPECT_GT(t.T_world_cam.t.norm(), 0.02);
    }
    if (t.status == tracking::TrackingStatus::kOk) {
      if (reinitialised == 0)
        last_ok = t.T_world_cam;
      else
        ++ok_after;
    }
  }
  EXPECT_GE(lost, config.pipeline.max_lost_ticks);
  EXPECT_GE(reinitialised, 1);
  EXPECT_GT(reinit_tick, 60u);
  // Tracking again once events return: most of the last 0.5 s.
  EXPECT_GT(ok_after, 40);
}

TEST(Odometry, TheSameTrajectoryBitForBitAtOneAndTwoThreads) {
  const OdometryConfig config = RpgPreset();
  std::vector<OdometryTick> one, two;
  {
    tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 1);
    one = RunMini(config);
  }
  {
    tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 2);
    two = RunMini(config);
  }
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i].T_world_cam.R, two[i].T_world_cam.R) << "tick " << i;
    ASSERT_EQ(one[i].T_world_cam.t, two[i].T_world_cam.t) << "tick " << i;
    ASSERT_EQ(one[i].status, two[i].status) << "tick " << i;
  }
}

// A rig without an IMU (the gyroscope mode configured all the same): every tick runs in the call
// that makes it due, none waits for IMU samples that never come.
TEST(Odometry, WithoutAnImuNoTickWaits) {
  const aavio::testing::SimulatedSequence& r = Mini();
  ASSERT_TRUE(r.rig.has_value());
  ASSERT_EQ(RpgPreset().imu.mode, imu::ImuMode::kGyro);
  Odometry odometry(*r.rig, RpgPreset(), r.start_ns);
  int ticks = 0;
  odometry.on_tick = [&](const OdometryTick&) { ++ticks; };
  for (std::size_t i = 0; i < 300 && i < r.packets.size(); ++i) {
    const io::SensorPacket& p = r.packets[i];
    ASSERT_TRUE(odometry.Process(p.left, p.right, {}, p.t_end_ns).ok());
    EXPECT_GE(odometry.next_tick_ns(), p.t_end_ns) << "packet " << i;
  }
  EXPECT_GE(ticks, 29);
}

// An IMU whose stamps run 7 ms late, with imu.time_offset_s saying so: the trajectory of the
// IMU on time, bit for bit (ticks wait for their samples). Not saying so changes it.
TEST(Odometry, TheImuTimeOffsetUndoesALateImuClock) {
  const TimeNs late_ns = 7 * kNsPerMs;
  const std::vector<OdometryTick> on_time = RunMini(RpgPreset());
  OdometryConfig config = RpgPreset();
  config.imu.time_offset_s = NsToSeconds(late_ns);
  const std::vector<OdometryTick> told = RunMini(config, -1.0, -1.0, late_ns);
  const std::vector<OdometryTick> untold = RunMini(RpgPreset(), -1.0, -1.0, late_ns);
  ASSERT_EQ(told.size(), on_time.size());
  ASSERT_EQ(untold.size(), on_time.size());
  // The last tick's window would need samples stamped past the recording's end.
  int differ_untold = 0;
  for (std::size_t i = 0; i + 1 < on_time.size(); ++i) {
    ASSERT_EQ(told[i].t_ns, on_time[i].t_ns);
    ASSERT_EQ(told[i].T_world_cam.R, on_time[i].T_world_cam.R) << "tick " << i;
    ASSERT_EQ(told[i].T_world_cam.t, on_time[i].T_world_cam.t) << "tick " << i;
    differ_untold += untold[i].T_world_cam.R != on_time[i].T_world_cam.R;
  }
  EXPECT_GT(differ_untold, static_cast<int>(on_time.size()) / 2);
}

TEST(Odometry, ShiftingEveryStampChangesNoPose) {
  // The same recording on other clocks (up to a UNIX time in ns): the same poses, bit for bit,
  // at the same times after the start.
  const std::vector<OdometryTick> base = RunMini(RpgPreset());
  ASSERT_GT(base.size(), 100u);
  for (const TimeNs shift_ns : {TimeNs{10'000'000'000}, TimeNs{1'700'000'000'123'456'789}}) {
    SCOPED_TRACE(shift_ns);
    const std::vector<OdometryTick> moved = RunMini(RpgPreset(), -1.0, -1.0, 0, {}, shift_ns);
    ASSERT_EQ(moved.size(), base.size());
    for (std::size_t i = 0; i < base.size(); ++i) {
      ASSERT_EQ(moved[i].t_ns - shift_ns, base[i].t_ns);
      ASSERT_EQ(moved[i].status, base[i].status) << i;
      ASSERT_EQ(moved[i].T_world_cam.R, base[i].T_world_cam.R) << i;
      ASSERT_EQ(moved[i].T_world_cam.t, base[i].T_world_cam.t) << i;
    }
  }
}

TEST(Odometry, AnHourWithoutEventsIsSkippedNotTickedThrough) {
  // The recording stops at 0.8 s and goes on an hour later (events and IMU alike).
  const aavio::testing::SimulatedSequence& r = Mini();
  ASSERT_TRUE(r.rig && !r.packets.empty());
  const TimeNs cut_ns = r.start_ns + SecondsToNs(0.8);
  const TimeNs hour_ns = 3600 * kNsPerS;
  Odometry odometry(*r.rig, RpgPreset(), r.start_ns);
  std::vector<OdometryTick> ticks;
  odometry.on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  TimeNs last_before = 0, first_after = 0;
  for (io::SensorPacket p : r.packets) {
    const TimeNs shift = p.t_begin_ns >= cut_ns ? hour_ns : 0;
    for (auto* events : {&p.left, &p.right})
      for (events::Event& e : *events) {
        e.t_ns += shift;
        if (shift == 0) last_before = std::max(last_before, e.t_ns);
        if (shift != 0 && first_after == 0) first_after = e.t_ns;
      }
    for (imu::ImuSample& sample : p.imu)
      sample.t_ns += shift;
    ASSERT_TRUE(odometry.Process(p.left, p.right, p.imu, p.t_end_ns + shift).ok());
  }
  ASSERT_TRUE(odometry.Finish().ok());
  // The ticks of the silent 5 s after the cut run (the pose holds), none of the hour's until the
  // one at or just before the events' return.
  std::size_t resumed = 0;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    ASSERT_TRUE(Finite(ticks[i].T_world_cam)) << i;
    ASSERT_TRUE(ticks[i].t_ns <= last_before + Odometry::kEventGapNs ||
                ticks[i].t_ns + SecondsToNs(0.01) > first_after)
        << NsToSeconds(ticks[i].t_ns - r.start_ns);
    if (ticks[i].gap_before) {
      ASSERT_EQ(resumed, 0u);
      resumed = i;
    }
  }
  ASSERT_GT(resumed, 0u);
  EXPECT_EQ(ticks[resumed].gap_before->from_ns, last_before);
  EXPECT_EQ(ticks[resumed].gap_before->to_ns, first_after);
  EXPECT_TRUE(ticks[resumed].reinitialised);
  EXPECT_LT(ticks.size(), 80u + 500u + 80u);  // 0.8 s + 5 s + what follows, at 100 Hz
  // On the same tick grid, and mapping starts again after the gap.
  EXPECT_EQ((ticks[resumed].t_ns - r.start_ns) % SecondsToNs(0.01), 0);
  bool bootstrapped = false;
  for (std::size_t i = resumed; i < ticks.size(); ++i)
    bootstrapped = bootstrapped || ticks[i].bootstrap;
  EXPECT_TRUE(bootstrapped);
}

TEST(Odometry, EventsStartingLateAreAGapButNoReinitialisation) {
  // The run starts 8 s before the first event (an IMU recording from earlier, say): no ticks
  // through the silence, and no map was thrown away.
  const aavio::testing::SimulatedSequence& r = Mini();
  ASSERT_TRUE(r.rig);
  Odometry odometry(*r.rig, RpgPreset(), r.start_ns - SecondsToNs(8.0));
  std::vector<OdometryTick> ticks;
  odometry.on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  for (const io::SensorPacket& p : r.packets)
    ASSERT_TRUE(odometry.Process(p.left, p.right, p.imu, p.t_end_ns).ok());
  ASSERT_TRUE(odometry.Finish().ok());
  ASSERT_FALSE(ticks.empty());
  ASSERT_TRUE(ticks.front().gap_before.has_value());
  EXPECT_EQ(ticks.front().gap_before->from_ns, r.start_ns - SecondsToNs(8.0));
  EXPECT_FALSE(ticks.front().reinitialised);
  EXPECT_GE(ticks.front().t_ns + SecondsToNs(0.01), ticks.front().gap_before->to_ns);
  int reinitialisations = 0, bootstraps = 0;
  for (const OdometryTick& t : ticks) {
    reinitialisations += t.reinitialised;
    bootstraps += t.bootstrap;
  }
  EXPECT_EQ(reinitialisations, 0);
  EXPECT_EQ(bootstraps, 1);
}

// The process's peak resident memory so far, in MB.
double PeakResidentMb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

TEST(Odometry, TenMillionEventsAtOneInstantAreCappedByMaxBufferedEvents) {
  const aavio::testing::SimulatedSequence& r = Mini();
  ASSERT_TRUE(r.rig);
  OdometryConfig config = RpgPreset();
  config.pipeline.max_buffered_events = 1000;
  Odometry odometry(*r.rig, config, r.start_ns);
  std::vector<OdometryTick> ticks;
  odometry.on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  // 10 million events per camera at one instant, handed over 100 000 at a time (as a driver
  // would): unbounded, they would hold 2 × 160 MB until the tick.
  const double peak_before_mb = PeakResidentMb();
  const TimeNs burst_ns = r.start_ns + SecondsToNs(0.005);
  std::vector<events::Event> chunk(100'000);
  for (std::size_t i = 0; i < chunk.size(); ++i)
    chunk[i] = {burst_ns, static_cast<std::uint16_t>(i % r.rig->width()),
                static_cast<std::uint16_t>(i % r.rig->height()), static_cast<std::uint8_t>(i % 2)};
  for (int c = 0; c < 100; ++c)
    ASSERT_TRUE(odometry.Process(chunk, chunk, {}, burst_ns + 1).ok());
  const Status ticked = odometry.Process({}, {}, {}, r.start_ns + SecondsToNs(0.05));
  ASSERT_TRUE(ticked.ok()) << ticked.message();
  ASSERT_TRUE(odometry.Finish().ok());
  ASSERT_FALSE(ticks.empty());
  EXPECT_EQ(ticks.back().dropped_events, 2 * (10'000'000 - 1000));
  EXPECT_EQ(ticks.front().new_events_left, 1000);
  EXPECT_LT(PeakResidentMb() - peak_before_mb, 64.0);
}

TEST(Odometry, ATrackTheAccelerometerContradictsIsLostAndMappingRestarts) {
  const std::vector<OdometryTick> plain = RunMini(RpgPreset());
  for (const OdometryTick& t : plain)
    ASSERT_NE(t.lost_reason, tracking::LostReason::kImuDisagrees) << NsToSeconds(t.t_ns);
  // From 0.7 s the accelerometer reads half as much again as it should (a wrong range setting):
  // the events show no such acceleration, so the tracked motion and the IMU disagree.
  const TimeNs from_ns = Mini().start_ns + SecondsToNs(0.7);
  const std::vector<OdometryTick> ticks =
      RunMini(RpgPreset(), -1.0, -1.0, 0, [from_ns](imu::ImuSample* s) {
        if (s->t_ns >= from_ns) s->accel_m_s2 *= 1.5;
      });
  std::optional<std::size_t> first;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    ASSERT_TRUE(Finite(ticks[i].T_world_cam));
    if (ticks[i].lost_reason == tracking::LostReason::kImuDisagrees && !first) first = i;
  }
  ASSERT_TRUE(first.has_value());
  const OdometryTick& lost = ticks[*first];
  EXPECT_EQ(lost.status, tracking::TrackingStatus::kLost);
  EXPECT_TRUE(lost.reinitialised);
  // Seen within 0.6 s (by the first three anchors 0.25 s apart after the change).
  EXPECT_GE(lost.t_ns, from_ns);
  EXPECT_LE(lost.t_ns, from_ns + SecondsToNs(0.6));
  // Mapping starts again: a new first map after it.
  bool bootstrapped = false;
  for (std::size_t i = *first + 1; i < ticks.size(); ++i)
    bootstrapped = bootstrapped || ticks[i].bootstrap;
  EXPECT_TRUE(bootstrapped);
}

}  // namespace
}  // namespace aavio::pipeline
