// Streaming use: packets of any size and order between streams give the same output as the
// odometry fed whole packets; real-time mode sheds ticks, never events; bad input is refused.
#include "aavio/pipeline/live_odometry.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <thread>

#include "tests/preset_config.hpp"
#include "tests/simulated_sequence.hpp"

namespace aavio::pipeline {
namespace {

const aavio::testing::SimulatedSequence& Mini() {
  return aavio::testing::MiniTwin(1.5, 3);
}

OdometryConfig Config() {
  return aavio::testing::MiniConfig(Mini().rig);
}

struct Streams {
  std::vector<events::Event> left, right;
  std::vector<imu::ImuSample> imu;
  TimeNs end_ns = 0;
};

Streams Concatenated() {
  Streams s;
  for (const io::SensorPacket& p : Mini().packets) {
    s.left.insert(s.left.end(), p.left.begin(), p.left.end());
    s.right.insert(s.right.end(), p.right.begin(), p.right.end());
    s.imu.insert(s.imu.end(), p.imu.begin(), p.imu.end());
    s.end_ns = p.t_end_ns;
  }
  return s;
}

/// The next data of each stream before `end_ns`, from where the last call stopped.
struct Chunk {
  std::span<const events::Event> left, right;
  std::span<const imu::ImuSample> imu;
};
class Chunker {
 public:
  explicit Chunker(const Streams& all) : all_(all) {}
  Chunk Next(TimeNs end_ns) {
    Chunk c;
    c.left = Take(all_.left, &l_, end_ns);
    c.right = Take(all_.right, &r_, end_ns);
    c.imu = Take(all_.imu, &m_, end_ns);
    return c;
  }
  bool done() const { return l_ == all_.left.size() && r_ == all_.right.size(); }

 private:
  template <typename T>
  static std::span<const T> Take(const std::vector<T>& v, std::size_t* next, TimeNs end_ns) {
    const std::size_t from = *next;
    while (*next < v.size() && v[*next].t_ns < end_ns)
      ++*next;
    return std::span<const T>(v).subspan(from, *next - from);
  }
  const Streams& all_;
  std::size_t l_ = 0, r_ = 0, m_ = 0;
};

/// Every stream's next data before `t`, each camera's declared complete up to `t`.
Status PushUntil(LiveOdometry& live, Chunker* chunker, TimeNs t) {
  const Chunk c = chunker->Next(t);
  AAVIO_RETURN_IF_ERROR(live.PushImu(c.imu));
  AAVIO_RETURN_IF_ERROR(live.PushEvents(events::Camera::kLeft, c.left, t));
  return live.PushEvents(events::Camera::kRight, c.right, t);
}

/// The reference: Odometry fed the reader's 1 ms packets.
std::vector<OdometryTick> Reference(const OdometryConfig& config) {
  Odometry odometry(*Mini().rig, config, Mini().start_ns);
  std::vector<OdometryTick> ticks;
  odometry.on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  for (const io::SensorPacket& p : Mini().packets)
    EXPECT_TRUE(odometry.Process(p.left, p.right, p.imu, p.t_end_ns).ok());
  EXPECT_TRUE(odometry.Finish().ok());
  return ticks;
}

// Also with an IMU time offset (4.3 ms: ticks wait for samples stamped past them, which random
// packets deliver at random moments).
class LiveOdometryPackets : public ::testing::TestWithParam<double> {};

TEST_P(LiveOdometryPackets, RandomPacketsGiveTheSameTrajectoryBitForBit) {
  ASSERT_TRUE(Mini().rig.has_value());
  OdometryConfig config = Config();
  config.imu.time_offset_s = GetParam();
  const std::vector<OdometryTick> reference = Reference(config);
  ASSERT_GT(reference.size(), 140u);
  const Streams all = Concatenated();
  // Three streams cut into packets of random length (1–4000 events, 1–30 samples), pushed in
  // a random interleaving, as three drivers would.
  std::mt19937 rng(7);
  auto live = LiveOdometry::Create(*Mini().rig, config, Mini().start_ns);
  ASSERT_TRUE(live.ok()) << live.status().message();
  std::vector<OdometryTick> ticks;
  (*live)->on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  std::size_t next[3] = {0, 0, 0};
  const std::size_t size[3] = {all.left.size(), all.right.size(), all.imu.size()};
  while (next[0] < size[0] || next[1] < size[1] || next[2] < size[2]) {
    const int stream = std::uniform_int_distribution<int>(0, 2)(rng);
    if (next[stream] >= size[stream]) continue;
    const std::size_t n = std::min<std::size_t>(
        size[stream] - next[stream],
        std::uniform_int_distribution<std::size_t>(1, stream == 2 ? 30 : 4000)(rng));
    Status s;
    if (stream == 2) {
      s = (*live)->PushImu(std::span(all.imu).subspan(next[2], n));
    } else {
      const auto& events = stream == 0 ? all.left : all.right;
      s = (*live)->PushEvents(stream == 0 ? events::Camera::kLeft : events::Camera::kRight,
                              std::span(events).subspan(next[stream], n));
    }
    ASSERT_TRUE(s.ok()) << s.message();
    next[stream] += n;
  }
  ASSERT_TRUE((*live)->Finish(all.end_ns).ok());
  ASSERT_EQ(ticks.size(), reference.size());
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    ASSERT_EQ(ticks[i].t_ns, reference[i].t_ns) << i;
    ASSERT_EQ(ticks[i].T_world_cam.R, reference[i].T_world_cam.R) << i;
    ASSERT_EQ(ticks[i].T_world_cam.t, reference[i].T_world_cam.t) << i;
    ASSERT_EQ(ticks[i].status, reference[i].status) << i;
    ASSERT_EQ(ticks[i].bootstrap, reference[i].bootstrap) << i;
    EXPECT_EQ(ticks[i].skipped_ticks, 0) << i;
  }
  const LiveStats stats = (*live)->stats();
  EXPECT_EQ(stats.events_processed[0], static_cast<std::int64_t>(all.left.size()));
  EXPECT_EQ(stats.events_processed[1], static_cast<std::int64_t>(all.right.size()));
  EXPECT_EQ(stats.ticks, static_cast<std::int64_t>(reference.size()));
  EXPECT_EQ(stats.skipped_ticks, 0);
}

INSTANTIATE_TEST_SUITE_P(ImuTimeOffset, LiveOdometryPackets, ::testing::Values(0.0, 0.0043));

TEST(LiveOdometry, RealTimeShedsTicksNeverEvents) {
  // The whole recording arrives at once, far faster than real time: the odometry must catch
  // up by skipping ticks, put every event into the time surfaces, say what it shed, and still
  // track.
  ASSERT_TRUE(Mini().rig.has_value());
  const Streams all = Concatenated();
  auto live = LiveOdometry::Create(*Mini().rig, Config(), Mini().start_ns,
                                   {.real_time = true, .max_lag_s = 0.02});
  ASSERT_TRUE(live.ok()) << live.status().message();
  std::vector<OdometryTick> ticks;
  (*live)->on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  // 50 ms of data per push, with no pause.
  const TimeNs step = 50 * kNsPerMs;
  Chunker chunker(all);
  for (TimeNs t = Mini().start_ns + step; !chunker.done(); t += step)
    ASSERT_TRUE(PushUntil(**live, &chunker, t).ok());
  ASSERT_TRUE((*live)->Finish(all.end_ns).ok());
  const LiveStats stats = (*live)->stats();
  EXPECT_EQ(stats.events_pushed[0], static_cast<std::int64_t>(all.left.size()));
  EXPECT_EQ(stats.events_processed[0], stats.events_pushed[0]);
  EXPECT_EQ(stats.events_processed[1], stats.events_pushed[1]);
  EXPECT_GT(stats.skipped_ticks, 0);
  EXPECT_GT(stats.max_backlog_s, 0.02);
  std::int64_t skipped = 0;
  for (const OdometryTick& t : ticks)
    skipped += t.skipped_ticks;
  EXPECT_EQ(skipped, stats.skipped_ticks);
  EXPECT_EQ(static_cast<std::int64_t>(ticks.size()), stats.ticks);
  // Every tick due was either run or skipped: 1.5 s at 100 Hz.
  EXPECT_EQ(stats.ticks + stats.skipped_ticks,
            static_cast<std::int64_t>(Reference(Config()).size()));
}

TEST(LiveOdometry, LatencyCountsFromThePushThatCompletedATicksData) {
  // Data pushed at its own pace (5 ms packets, at real time): a tick's latency is the time from
  // the push of its last data to its pose — milliseconds —, not from the start of the data
  // (which would put the median near 0.75 s).
  ASSERT_TRUE(Mini().rig.has_value());
  const Streams all = Concatenated();
  auto live = LiveOdometry::Create(*Mini().rig, Config(), Mini().start_ns, {.real_time = true});
  ASSERT_TRUE(live.ok()) << live.status().message();
  EXPECT_EQ((*live)->stats().latency_median_ms, 0.0);
  const TimeNs step = 5 * kNsPerMs;
  Chunker chunker(all);
  const auto wall_start = std::chrono::steady_clock::now();
  for (TimeNs t = Mini().start_ns + step; !chunker.done(); t += step) {
    std::this_thread::sleep_until(wall_start + std::chrono::nanoseconds(t - Mini().start_ns));
    ASSERT_TRUE(PushUntil(**live, &chunker, t).ok());
  }
  ASSERT_TRUE((*live)->Finish(all.end_ns).ok());
  const LiveStats stats = (*live)->stats();
  // Every tick due is run or shed (a slow build, e.g. with sanitizers, sheds some).
  EXPECT_EQ(stats.ticks + stats.skipped_ticks, 150);
  EXPECT_GT(stats.ticks, 0);
  EXPECT_GT(stats.latency_median_ms, 0.0);
  EXPECT_LT(stats.latency_median_ms, 400.0);
  EXPECT_LE(stats.latency_median_ms, stats.latency_p99_ms);
  EXPECT_LE(stats.latency_p99_ms, stats.latency_max_ms * 1.01);  // the quantiles are within 0.5 %
}

TEST(LiveOdometry, TrackingHoldsWhenTwoTicksInThreeAreShed) {
  // What real-time mode does when behind, made deterministic: 30 ms of data per call, only the
  // newest tick run. The camera is still followed (as odometry_test's full run: the end within
  // 10 cm of the truth; mini moves about 40 cm in 1.5 s).
  ASSERT_TRUE(Mini().rig.has_value());
  const Streams all = Concatenated();
  Odometry odometry(*Mini().rig, Config(), Mini().start_ns);
  std::vector<OdometryTick> ticks;
  odometry.on_tick = [&](const OdometryTick& t) { ticks.push_back(t); };
  Chunker chunker(all);
  for (TimeNs t = Mini().start_ns + 30 * kNsPerMs; !chunker.done(); t += 30 * kNsPerMs) {
    const TimeNs end = std::min(t, all.end_ns);
    const Chunk c = chunker.Next(end);
    ASSERT_TRUE(odometry.Process(c.left, c.right, c.imu, end, TickPolicy::kLatest).ok());
  }
  ASSERT_TRUE(odometry.Finish().ok());
  ASSERT_GT(ticks.size(), 45u);
  int ok = 0, skipped = 0;
  for (const OdometryTick& t : ticks) {
    ok += t.status == tracking::TrackingStatus::kOk;
    skipped += t.skipped_ticks;
    EXPECT_LE(t.skipped_ticks, 2);
  }
  EXPECT_EQ(ticks.size() + skipped, Reference(Config()).size());
  EXPECT_GT(ok, static_cast<int>(ticks.size()) * 8 / 10);
  const geometry::StampedPose& truth_start = Mini().truth.front();
  const geometry::StampedPose& truth_end = Mini().truth.back();
  const Eigen::Vector3d truth_moved = truth_start.T_world_body.R.transpose() *
                                      (truth_end.T_world_body.t - truth_start.T_world_body.t);
  EXPECT_LT((ticks.back().T_world_cam.t - truth_moved).norm(), 0.10)
      << ticks.back().T_world_cam.t.transpose() << " vs " << truth_moved.transpose();
}

TEST(LiveOdometry, RefusesDataOutOfOrderAndAbsurdOptions) {
  ASSERT_TRUE(Mini().rig.has_value());
  auto bad = LiveOdometry::Create(*Mini().rig, Config(), 0, {.max_lag_s = -1.0});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("max_lag_s"), std::string::npos);

  auto live = LiveOdometry::Create(*Mini().rig, Config(), 0);
  ASSERT_TRUE(live.ok());
  const std::vector<events::Event> late = {{2000, 1, 1, 1}, {1000, 2, 2, 0}};
  const Status s = (*live)->PushEvents(events::Camera::kRight, late);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("right event at t = 1000 ns"), std::string::npos) << s.message();
  ASSERT_TRUE((*live)->PushEvents(events::Camera::kLeft, {}, 5000).ok());
  const std::vector<events::Event> before = {{4000, 1, 1, 1}};
  EXPECT_FALSE((*live)->PushEvents(events::Camera::kLeft, before).ok());
  const std::vector<imu::ImuSample> imu = {{.t_ns = 10}, {.t_ns = 5}};
  EXPECT_NE((*live)->PushImu(imu).message().find("IMU sample at t = 5 ns"), std::string::npos);
  std::vector<imu::ImuSample> nan_gyro = {{.t_ns = 20}}, infinite_accel = {{.t_ns = 30}};
  nan_gyro[0].gyro_rad_s.y() = std::nan("");
  infinite_accel[0].accel_m_s2.z() = std::numeric_limits<double>::infinity();
  EXPECT_NE((*live)->PushImu(nan_gyro).message().find("t = 20 ns reads a rate that is not finite"),
            std::string::npos);
  EXPECT_NE((*live)->PushImu(infinite_accel).message().find("specific force that is not finite"),
            std::string::npos);
  ASSERT_TRUE((*live)->Finish().ok());
  EXPECT_EQ((*live)->PushImu({}).code(), StatusCode::kFailedPrecondition);
}

}  // namespace
}  // namespace aavio::pipeline
