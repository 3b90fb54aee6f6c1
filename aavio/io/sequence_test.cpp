#include "aavio/io/sequence.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/event_fixtures.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

using testing::Fixture;

TEST(Sequence, ReadsASequenceYamlWithRelativePaths) {
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "calib" / "left.yaml", testing::kRpgLeftYaml);
  testing::WriteFile(dir / "calib" / "right.yaml", testing::kRpgRightYaml);
  std::filesystem::create_directories(dir / "data");
  std::filesystem::copy_file(Fixture("bag_lz4.bag"), dir / "data" / "recording.bag");
  const std::string yaml = testing::WriteFile(dir / "sequence.yaml",
                                              "name: box\n"
                                              "calibration: calib\n"
                                              "events:\n"
                                              "  left: data/recording.bag\n"
                                              "  right: data/recording.bag\n"
                                              "imu:\n"
                                              "  path: data/recording.bag\n"
                                              "ground_truth:\n"
                                              "  trajectory: data/recording.bag\n"
                                              "  topic: /gt/pose\n");
  Expected<SequenceDescription> d = DescribeSequence(dir.string());
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_EQ(d->name, "box");
  EXPECT_EQ(d->calibration, (dir / "calib").string());
  EXPECT_EQ(d->left.format, SourceFormat::kBag);
  EXPECT_EQ(d->left.topic, "/davis/left/events");
  EXPECT_EQ(d->right.topic, "/davis/right/events");
  ASSERT_TRUE(d->imu.has_value());
  EXPECT_EQ(d->gt_trajectory->topic, "/gt/pose");

  // Packets cover the data without gaps or overlaps, and hold every element once.
  Expected<std::unique_ptr<SequenceReader>> reader = SequenceReader::Open(
      *d, {.packet_ns = 3 * kNsPerMs, .stream = {.width = 240, .height = 180}});
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  SensorPacket packet;
  std::size_t left = 0, right = 0, imu = 0;
  TimeNs previous_end = (*reader)->start_ns();
  while (true) {
    Expected<bool> more = (*reader)->Next(&packet);
    ASSERT_TRUE(more.ok()) << more.status().message();
    if (!*more) break;
    EXPECT_EQ(packet.t_begin_ns, previous_end);
    previous_end = packet.t_end_ns;
    for (const events::Event& e : packet.left) {
      EXPECT_GE(e.t_ns, packet.t_begin_ns);
      EXPECT_LT(e.t_ns, packet.t_end_ns);
    }
    left += packet.left.size();
    right += packet.right.size();
    imu += packet.imu.size();
  }
  EXPECT_EQ(left, testing::ExpectedEvents("bag_lz4.left").size());
  EXPECT_EQ(right, testing::ExpectedEvents("bag_lz4.right").size());
  EXPECT_EQ(imu, testing::ExpectedImu("bag_lz4").size());
}

TEST(Sequence, StreamsThatDoNotOverlapAreRefusedWithBothSpans) {
  SequenceDescription d;
  d.origin = "seq/sequence.yaml";
  const StreamInfo left{.count = 10, .t_first_ns = kNsPerS, .t_last_ns = 2 * kNsPerS};
  StreamInfo right = left;
  EXPECT_TRUE(CheckStreamsOverlap(d, left, right, nullptr).ok());
  right.t_first_ns = 5 * kNsPerS;
  right.t_last_ns = 6 * kNsPerS;
  EXPECT_EQ(CheckStreamsOverlap(d, left, right, nullptr).message(),
            "seq/sequence.yaml: the left camera's events span 1.000000000 - 2.000000000 s and the "
            "right camera's 5.000000000 - 6.000000000 s: they do not overlap; are both from this "
            "recording, and on one clock?");
  // An IMU 1000 s late: host time against sensor time.
  const StreamInfo imu{.count = 10, .t_first_ns = 1001 * kNsPerS, .t_last_ns = 1002 * kNsPerS};
  const Status late = CheckStreamsOverlap(d, left, left, &imu);
  EXPECT_NE(late.message().find("the IMU samples span 1001.000000000 - 1002.000000000 s and the "
                                "events 1.000000000 - 2.000000000 s: they do not overlap"),
            std::string::npos)
      << late.message();
  // A span not known without reading the whole stream is not checked.
  EXPECT_TRUE(CheckStreamsOverlap(d, left, StreamInfo{}, &imu).ok());
}

TEST(Sequence, AnImuTheTrackerCannotUseIsSaid) {
  SequenceDescription d;
  EXPECT_EQ(ImuStreamWarning(d, 0, 0, 0, 100.0), "");  // no IMU named: nothing to say
  d.imu = SourceSpec{SourceFormat::kText, "imu.txt", "", ImuTextLayout::kEcd};
  EXPECT_EQ(ImuStreamWarning(d, 0, 0, 0, 100.0),
            "imu.txt: no IMU samples in the time processed; the run went on without an IMU (check "
            "the topic, the file or its stamps)");
  EXPECT_NE(ImuStreamWarning(d, 11, 0, 10 * kNsPerS, 100.0)
                .find("imu.txt: 1.0 IMU samples per second, fewer than one per tick (100 Hz)"),
            std::string::npos);
  EXPECT_EQ(ImuStreamWarning(d, 2001, 0, 10 * kNsPerS, 100.0), "");  // 200 Hz
}

TEST(Sequence, AGapOfHoursIsReadInFewPacketsOfBoundedLength) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "gap_sequence";
  std::filesystem::create_directories(dir);
  for (const char* side : {"left", "right"}) {
    std::ofstream out(dir / (std::string(side) + ".txt"));
    for (int i = 0; i < 100; ++i)
      out << 0.001 * i << " 1 1 1\n";
    out << "10800.5 2 2 0\n";  // three hours later
  }
  SequenceDescription d;
  d.left = {SourceFormat::kText, (dir / "left.txt").string(), "", {}};
  d.right = {SourceFormat::kText, (dir / "right.txt").string(), "", {}};
  Expected<std::unique_ptr<SequenceReader>> reader = SequenceReader::Open(d, {});
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  SensorPacket packet;
  std::size_t packets = 0, events = 0;
  TimeNs previous_end = (*reader)->start_ns();
  while (*(*reader)->Next(&packet)) {
    ++packets;
    events += packet.left.size();
    EXPECT_EQ(packet.t_begin_ns, previous_end);
    EXPECT_LE(packet.t_end_ns - packet.t_begin_ns, kNsPerS);
    previous_end = packet.t_end_ns;
  }
  EXPECT_EQ(events, 101u);
  EXPECT_LT(packets, 25000u);  // 10 800 s in packets of 0.512 s, not 10.8 million of 1 ms
}

TEST(Sequence, OneFileForBothCamerasIsRefused) {
  SequenceDescription d;
  d.origin = "seq/sequence.yaml";
  d.left = {SourceFormat::kDsecH5, Fixture("dsec_blosc.h5"), "", {}};
  d.right = d.left;
  const Status refused = SequenceReader::Open(d, {}).status();
  EXPECT_NE(refused.message().find("seq/sequence.yaml: the left and the right camera both read"),
            std::string::npos)
      << refused.message();
  // One bag holds both cameras under two topics.
  d.left = {SourceFormat::kBag, Fixture("bag_lz4.bag"), "/davis/left/events", {}};
  d.right = {SourceFormat::kBag, Fixture("bag_lz4.bag"), "/davis/right/events", {}};
  EXPECT_TRUE(SequenceReader::Open(d, {}).ok());
}

TEST(Sequence, PassesRepeatTheSequenceOnAContinuingClock) {
  SequenceDescription d;
  d.left = {SourceFormat::kDsecH5, Fixture("dsec_blosc.h5"), "", {}};
  // The same events from a second file: one file for both cameras is refused.
  d.right = d.left;
  d.right.path = ::testing::TempDir() + "/repeat_right.h5";
  std::filesystem::copy_file(d.left.path, d.right.path,
                             std::filesystem::copy_options::overwrite_existing);
  const SequenceReaderOptions options{.packet_ns = 10 * kNsPerMs, .passes = 3};
  Expected<std::unique_ptr<SequenceReader>> reader = SequenceReader::Open(d, options);
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  const std::vector<events::Event> once = testing::ExpectedEvents("dsec_blosc");
  const TimeNs start = (*reader)->start_ns();
  // One pass is a whole number of packets covering the data.
  const TimeNs period = ((once.back().t_ns - start) / options.packet_ns + 1) * options.packet_ns;
  EXPECT_EQ((*reader)->end_ns(), once.back().t_ns + 2 * period);
  SensorPacket packet;
  std::vector<events::Event> left;
  TimeNs previous_end = start;
  while (true) {
    Expected<bool> more = (*reader)->Next(&packet);
    ASSERT_TRUE(more.ok()) << more.status().message();
    if (!*more) break;
    EXPECT_EQ(packet.t_begin_ns, previous_end);  // the clock goes on across the seams
    previous_end = packet.t_end_ns;
    left.insert(left.end(), packet.left.begin(), packet.left.end());
  }
  ASSERT_EQ(left.size(), 3 * once.size());
  for (std::size_t pass = 0; pass < 3; ++pass) {
    for (std::size_t i : {std::size_t{0}, once.size() / 2, once.size() - 1}) {
      events::Event expected = once[i];
      expected.t_ns += static_cast<TimeNs>(pass) * period;
      EXPECT_EQ(left[pass * once.size() + i], expected) << "pass " << pass << ", event " << i;
    }
  }
  // Seeking into the second pass reads on from there.
  ASSERT_TRUE((*reader)->Seek(start + period + 20 * kNsPerMs).ok());
  ASSERT_TRUE((*reader)->Next(&packet).ok());
  EXPECT_EQ(packet.t_begin_ns, start + period + 20 * kNsPerMs);
  ASSERT_FALSE(packet.left.empty());
  EXPECT_GE(packet.left.front().t_ns, packet.t_begin_ns);
}

TEST(Sequence, WrittenDescriptionReadsBack) {
  const auto dir = testing::ScratchDir();
  SequenceDescription d;
  d.name = "twin";
  d.calibration = (dir / "calibration").string();
  d.left = {SourceFormat::kDsecH5, (dir / "events" / "left" / "events.h5").string(), "", {}};
  d.right = {SourceFormat::kDsecH5, (dir / "events" / "right" / "events.h5").string(), "", {}};
  d.imu = SourceSpec{SourceFormat::kText, (dir / "imu.txt").string(), "", ImuTextLayout::kEcd};
  d.gt_trajectory = SourceSpec{SourceFormat::kText, (dir / "groundtruth.txt").string(), "", {}};
  d.gt_depth = (dir / "depth").string();
  d.gt_calibration = (dir / "calibration_true").string();
  ASSERT_TRUE(WriteSequenceYaml((dir / "sequence.yaml").string(), d).ok());
  const std::vector<char> bytes = testing::ReadBytes((dir / "sequence.yaml").string());
  const std::string text(bytes.begin(), bytes.end());
  EXPECT_NE(text.find("left: events/left/events.h5"), std::string::npos) << text;  // relative
  Expected<SequenceDescription> back = ReadSequenceYaml((dir / "sequence.yaml").string());
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->left.path, d.left.path);
  EXPECT_EQ(back->calibration, d.calibration);
  EXPECT_EQ(back->imu->path, d.imu->path);
  EXPECT_EQ(back->gt_trajectory->path, d.gt_trajectory->path);
  EXPECT_EQ(back->gt_depth, d.gt_depth);
  EXPECT_EQ(back->gt_calibration, d.gt_calibration);
}

TEST(Sequence, DsecFolderAndBagAreRecognised) {
  const auto dir = testing::ScratchDir();
  std::filesystem::create_directories(dir / "events" / "left");
  std::filesystem::create_directories(dir / "events" / "right");
  std::filesystem::copy_file(Fixture("dsec_blosc.h5"), dir / "events" / "left" / "events.h5");
  std::filesystem::copy_file(Fixture("dsec_blosc.h5"), dir / "events" / "right" / "events.h5");
  Expected<SequenceDescription> d = DescribeSequence(dir.string());
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_EQ(d->left.format, SourceFormat::kDsecH5);
  EXPECT_FALSE(d->imu.has_value());
  Expected<SequenceDescription> bag = DescribeSequence(Fixture("bag_none.bag"), "/some/calib");
  ASSERT_TRUE(bag.ok()) << bag.status().message();
  EXPECT_EQ(bag->calibration, "/some/calib");
  EXPECT_TRUE(bag->imu.has_value());
  EXPECT_TRUE(bag->gt_trajectory.has_value());
}

TEST(Sequence, BadDescriptionsGiveClearErrors) {
  struct Case {
    const char* yaml;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"calibration: c\n", "missing key 'events'"},
      {"events:\n  left: a.h5\n", "missing key 'events.right'"},
      {"events:\n  left: a.h5\n  rigth: b.h5\n",
       "unknown key 'events.rigth'; did you mean 'events.right'?"},
      {"events:\n  left: a.csv\n  right: b.h5\n", "unknown data format '.csv'"},
      {"evnts:\n  left: a.h5\n", "unknown key 'evnts'; did you mean 'events'?"},
      {"events:\n  left: a.h5\n  right: b.h5\nimu:\n  path: imu.txt\n  layout: csv\n",
       "imu.layout 'csv' must be ecd or tum_vie"},
      {"events:\n  [left]: a.h5\n  right: b.h5\n",
       "sequence.yaml:2: a key under 'events.' is a list or a map, not a name"},
      {"? {events: 1}\n: x\n", "a key is a list or a map, not a name"},
      {"events:\n  left: a.h5\n  right: b.h5\nground_truth:\n  trajectory: gt.h5\n",
       "ground_truth.trajectory must be a TUM .txt, a EuRoC .csv or a ROS1 .bag"},
  };
  for (const Case& c : cases) {
    const auto dir = testing::ScratchDir();
    const std::string path = testing::WriteFile(dir / "sequence.yaml", c.yaml);
    Expected<SequenceDescription> d = ReadSequenceYaml(path);
    ASSERT_FALSE(d.ok()) << c.yaml;
    EXPECT_NE(d.status().message().find(c.expected), std::string::npos) << d.status().message();
  }
  // EuRoC ground truth (.csv) is text, read as the eval reads it.
  const auto dir = testing::ScratchDir();
  const std::string euroc = testing::WriteFile(
      dir / "gt.csv",
      "#timestamp [ns], p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z []\n1000000000,0,0,0,1,0,0,0\n1010000000,0.1,0,0,1,0,0,0\n");
  Expected<SequenceDescription> with_csv = ReadSequenceYaml(testing::WriteFile(
      dir / "sequence.yaml",
      "events:\n  left: a.h5\n  right: b.h5\nground_truth:\n  trajectory: gt.csv\n"));
  ASSERT_TRUE(with_csv.ok()) << with_csv.status().message();
  EXPECT_EQ(with_csv->gt_trajectory->format, SourceFormat::kText);
  Expected<std::vector<geometry::StampedPose>> poses =
      ReadGroundTruthPoses(*with_csv->gt_trajectory);
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 2u);
  EXPECT_EQ((*poses)[1].t_ns, 1010000000);
  EXPECT_NE(
      DescribeSequence(testing::ScratchDir().string()).status().message().find("no sequence here"),
      std::string::npos);
}

}  // namespace
}  // namespace aavio::io
