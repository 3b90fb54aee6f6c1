// The library's run loop: the odometry it drives gives what Odometry fed packet by packet gives,
// with or without prefetching; it stops where asked, on the consumer's error and at end_ns, and
// says how far it got.
#include "aavio/pipeline/sequence_run.hpp"

#include <gtest/gtest.h>

#include "tests/preset_config.hpp"
#include "tests/simulated_sequence.hpp"

namespace aavio::pipeline {
namespace {

constexpr TimeNs kPacketNs = 10 * kNsPerMs;

const aavio::testing::SimulatedSequence& Mini() {
  return aavio::testing::MiniTwin(1.0, 5, kPacketNs);
}

OdometryConfig Config() {
  return aavio::testing::MiniConfig(Mini().rig);
}

std::unique_ptr<io::SequenceReader> OpenMini() {
  io::SequenceReaderOptions options;
  options.packet_ns = kPacketNs;
  Expected<std::unique_ptr<io::SequenceReader>> reader =
      io::SequenceReader::Open(Mini().description, options);
  EXPECT_TRUE(reader.ok()) << reader.status().message();
  return reader.ok() ? std::move(*reader) : nullptr;
}

struct Ran {
  SequenceRun run;
  std::vector<geometry::StampedPose> poses;
};

Ran RunMini(const SequenceRunHooks& hooks, TimeNs end_ns = 0) {
  Ran ran;
  std::unique_ptr<io::SequenceReader> reader = OpenMini();
  if (!reader) return ran;
  Odometry odometry(*Mini().rig, Config(), Mini().start_ns);
  odometry.on_tick = [&ran](const OdometryTick& t) {
    ran.poses.push_back({t.t_ns, t.T_world_cam});
  };
  ran.run = RunOdometry(*reader, Mini().start_ns, end_ns > 0 ? end_ns : reader->end_ns(), &odometry,
                        hooks);
  return ran;
}

void ExpectSamePoses(const std::vector<geometry::StampedPose>& a,
                     const std::vector<geometry::StampedPose>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].t_ns, b[i].t_ns) << i;
    ASSERT_EQ(a[i].T_world_body.t, b[i].T_world_body.t) << "pose " << i;
    ASSERT_EQ(a[i].T_world_body.R, b[i].T_world_body.R) << "pose " << i;
  }
}

TEST(SequenceRun, DrivesTheOdometryAsPacketsFedByHandWithOrWithoutPrefetching) {
  if (!Mini().rig) GTEST_SKIP();
  const std::unique_ptr<io::SequenceReader> reader = OpenMini();
  ASSERT_TRUE(reader);
  const TimeNs end_ns = reader->end_ns();  // the last stamp: the last packet is cut there
  Odometry odometry(*Mini().rig, Config(), Mini().start_ns);
  std::vector<geometry::StampedPose> by_hand;
  odometry.on_tick = [&](const OdometryTick& t) { by_hand.push_back({t.t_ns, t.T_world_cam}); };
  std::int64_t events = 0, imu = 0;
  for (const io::SensorPacket& p : Mini().packets) {
    ASSERT_TRUE(odometry.Process(p.left, p.right, p.imu, std::min(p.t_end_ns, end_ns)).ok());
    events += static_cast<std::int64_t>(p.left.size() + p.right.size());
    imu += static_cast<std::int64_t>(p.imu.size());
  }
  ASSERT_TRUE(odometry.Finish().ok());
  ASSERT_GT(by_hand.size(), 50u);

  for (int prefetch : {0, 50}) {
    SCOPED_TRACE(prefetch);
    const Ran ran = RunMini({.prefetch_packets = prefetch});
    EXPECT_TRUE(ran.run.stopped_by.ok()) << ran.run.stopped_by.message();
    EXPECT_FALSE(ran.run.interrupted);
    EXPECT_EQ(ran.run.packets, static_cast<std::int64_t>(Mini().packets.size()));
    EXPECT_EQ(ran.run.events, events);
    EXPECT_EQ(ran.run.imu_samples, imu);
    EXPECT_EQ(ran.run.reached_ns, end_ns);
    ExpectSamePoses(ran.poses, by_hand);
  }
}

TEST(SequenceRun, StopsWhenAskedAndFinishesTheDataProcessed) {
  if (!Mini().rig) GTEST_SKIP();
  int asked = 0;
  std::vector<std::int64_t> progress;
  SequenceRunHooks hooks;
  hooks.stop = [&asked] { return ++asked > 30; };
  hooks.progress_every = 10;
  hooks.on_progress = [&progress](const SequenceRun& run) { progress.push_back(run.packets); };
  const Ran ran = RunMini(hooks);
  EXPECT_TRUE(ran.run.interrupted);
  EXPECT_TRUE(ran.run.stopped_by.ok());
  EXPECT_EQ(ran.run.packets, 30);
  EXPECT_EQ(ran.run.reached_ns, Mini().packets[29].t_end_ns);
  EXPECT_EQ(progress, (std::vector<std::int64_t>{1, 11, 21}));
  // Finish ran the ticks up to where it stopped (every 10 ms tick of the first 300 ms).
  ASSERT_FALSE(ran.poses.empty());
  EXPECT_GT(ran.poses.back().t_ns, Mini().packets[29].t_end_ns - 20 * kNsPerMs);
  EXPECT_LT(ran.poses.back().t_ns, Mini().packets[29].t_end_ns);
}

TEST(SequenceRun, EndsAtEndNsWithTheDataCompleteUpToIt) {
  if (!Mini().rig) GTEST_SKIP();
  const TimeNs end_ns = Mini().start_ns + 255 * kNsPerMs;  // inside a packet
  std::unique_ptr<io::SequenceReader> reader = OpenMini();
  ASSERT_TRUE(reader);
  std::vector<TimeNs> complete;
  const SequenceRun run = RunSequence(*reader, Mini().start_ns, end_ns,
                                      [&complete](const io::SensorPacket&, TimeNs complete_ns) {
                                        complete.push_back(complete_ns);
                                        return Status::Ok();
                                      });
  ASSERT_TRUE(run.stopped_by.ok());
  ASSERT_FALSE(complete.empty());
  EXPECT_EQ(complete.back(), end_ns);
  EXPECT_EQ(run.reached_ns, end_ns);
  EXPECT_EQ(run.packets, static_cast<std::int64_t>(complete.size()));
}

TEST(SequenceRun, AnErrorOfTheConsumerOrAHookStopsItThere) {
  if (!Mini().rig) GTEST_SKIP();
  for (const bool in_hook : {false, true}) {
    SCOPED_TRACE(in_hook);
    std::unique_ptr<io::SequenceReader> reader = OpenMini();
    ASSERT_TRUE(reader);
    int seen = 0;
    auto fifth_fails = [&seen] { return ++seen == 5 ? IoError("disk full") : Status::Ok(); };
    SequenceRunHooks hooks;
    if (in_hook) hooks.after_packet = [&](const io::SensorPacket&) { return fifth_fails(); };
    const SequenceRun run = RunSequence(
        *reader, Mini().start_ns, reader->end_ns(),
        [&](const io::SensorPacket&, TimeNs) { return in_hook ? Status::Ok() : fifth_fails(); },
        hooks);
    EXPECT_FALSE(run.stopped_by.ok());
    EXPECT_EQ(run.stopped_by.message(), "disk full");
    EXPECT_EQ(run.packets, 4);
    EXPECT_EQ(run.reached_ns, Mini().packets[3].t_end_ns);
  }
}

}  // namespace
}  // namespace aavio::pipeline
