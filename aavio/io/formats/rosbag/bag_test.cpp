// ROS1 bags written by python3-rosbag + genpy (independent), and our writer's bags read back by
// python3-rosbag (tests/fixtures/check_bag.py) and by our reader.
#include <gtest/gtest.h>

#include "aavio/io/formats/rosbag/bag_streams.hpp"
#include "aavio/io/formats/rosbag/bag_writer.hpp"
#include "tests/event_fixtures.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

using testing::ExpectedEvents;
using testing::Fixture;

class BagVariants : public ::testing::TestWithParam<const char*> {};

TEST_P(BagVariants, EventsOfBothTopicsInEventTime) {
  const std::string name = GetParam();
  for (const char* side : {"left", "right"}) {
    auto stream =
        BagEventStream::Open(Fixture(name + ".bag"), std::string("/davis/") + side + "/events", {});
    ASSERT_TRUE(stream.ok()) << stream.status().message();
    const std::vector<events::Event> expected = ExpectedEvents(name + "." + side);
    EXPECT_EQ((*stream)->info().t_first_ns, expected.front().t_ns);
    EXPECT_EQ((*stream)->info().t_last_ns, expected.back().t_ns);
    EXPECT_EQ((*stream)->info().width, 240);
    EXPECT_EQ((*stream)->info().height, 180);
    const std::vector<events::Event> got = testing::ReadAllOf(**stream, kNsPerMs);
    ASSERT_EQ(got.size(), expected.size()) << name << " " << side;
    EXPECT_TRUE(got == expected) << name << " " << side;
  }
}

TEST_P(BagVariants, ImuFoundByTypeAndPoses) {
  const std::string name = GetParam();
  auto imu = BagImuStream::Open(Fixture(name + ".bag"), "", {});
  ASSERT_TRUE(imu.ok()) << imu.status().message();
  const std::vector<imu::ImuSample> expected = testing::ExpectedImu(name);
  const std::vector<imu::ImuSample> got = testing::ReadAllOf(**imu, 7 * kNsPerMs);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t_ns, expected[i].t_ns);
    EXPECT_EQ(got[i].gyro_rad_s, expected[i].gyro_rad_s);
    EXPECT_EQ(got[i].accel_m_s2, expected[i].accel_m_s2);
  }
  Expected<std::vector<geometry::StampedPose>> poses = ReadBagPoses(Fixture(name + ".bag"), "");
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  const std::vector<geometry::StampedPose> expected_poses = testing::ExpectedPoses(name);
  ASSERT_EQ(poses->size(), expected_poses.size());
  for (std::size_t i = 0; i < poses->size(); ++i) {
    EXPECT_EQ((*poses)[i].t_ns, expected_poses[i].t_ns);
    EXPECT_LT(((*poses)[i].T_world_body.t - expected_poses[i].T_world_body.t).norm(), 1e-15);
  }
}

// Compression none / bz2 / lz4 (dvs_msgs left, dv_ros_msgs right) and prophesee type names.
INSTANTIATE_TEST_SUITE_P(Fixtures, BagVariants,
                         ::testing::Values("bag_none", "bag_bz2", "bag_lz4", "bag_prophesee"));

TEST(Bag, SeekStartsAtTheTarget) {
  const std::vector<events::Event> expected = ExpectedEvents("bag_lz4.left");
  auto stream = BagEventStream::Open(Fixture("bag_lz4.bag"), "/davis/left/events", {});
  ASSERT_TRUE(stream.ok());
  for (std::size_t k : {0ul, 5000ul, 19999ul}) {
    const TimeNs target = expected[k].t_ns;
    ASSERT_TRUE((*stream)->Seek(target).ok());
    std::vector<events::Event> out;
    ASSERT_TRUE((*stream)->ReadUntil(target + kNsPerMs, &out).ok());
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.front(), expected[k]);
  }
}

TEST(Bag, MissingTopicsListTheTopicsThatExist) {
  auto stream = BagEventStream::Open(Fixture("bag_other_topic.bag"), "/davis/left/events", {});
  ASSERT_FALSE(stream.ok());
  EXPECT_NE(stream.status().message().find(
                "no topic '/davis/left/events'; topics: /cam0/events (dvs_msgs/EventArray, "),
            std::string::npos)
      << stream.status().message();
  auto imu = BagImuStream::Open(Fixture("bag_no_imu.bag"), "", {});
  ASSERT_FALSE(imu.ok());
  EXPECT_NE(imu.status().message().find("no sensor_msgs/Imu topic; topics: /davis/left/events"),
            std::string::npos)
      << imu.status().message();
  // The IMU topic holds the wrong type.
  auto wrong = BagEventStream::Open(Fixture("bag_none.bag"), "/davis/left/imu", {});
  EXPECT_NE(wrong.status().message().find("has type sensor_msgs/Imu"), std::string::npos);
}

TEST(Bag, BrokenBagsGiveClearErrors) {
  struct Case {
    const char* file;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"bag_truncated.bag", "the bag is truncated; `rosbag reindex` may recover it"},
      {"bag_legacy.bag", "pre-2017 dvs_msgs/EventArray layout"},
      {"not_a_bag.bag", "a ROS bag of format 1.2"},
      {"events.txt", "not a ROS1 bag"},
      {"bag_corrupt.bag", "chunk 0 at byte 4117: record cut short"},
      {"bag_corrupt_lz4.bag", "chunk 0 at byte 4117: corrupt LZ4 data"},
  };
  for (const Case& c : cases) {
    auto stream = BagEventStream::Open(Fixture(c.file), "/davis/left/events", {});
    Status s = stream.status();
    if (stream.ok()) {
      std::vector<events::Event> out;
      while (s.ok() && !(*stream)->AtEnd())
        s = (*stream)->ReadUntil((*stream)->info().t_last_ns + 1, &out);
    }
    ASSERT_FALSE(s.ok()) << c.file;
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << c.file << ": " << s.message();
  }
}

TEST(Bag, EventsOutsideTheSensorAreRefused) {
  auto stream = BagEventStream::Open(Fixture("bag_none.bag"), "/davis/left/events",
                                     {.width = 200, .height = 180});
  Status s = stream.status();
  std::vector<events::Event> out;
  while (s.ok() && !(*stream)->AtEnd())
    s = (*stream)->ReadUntil((*stream)->info().t_last_ns + 1, &out);
  EXPECT_NE(s.message().find("is outside the 200x180 sensor"), std::string::npos) << s.message();
}

class BagWriterTest : public ::testing::TestWithParam<BagCompression> {};

TEST_P(BagWriterTest, RoundTripsAndRosbagAgrees) {
  const std::vector<events::Event> left = ExpectedEvents("bag_lz4.left");
  const std::vector<events::Event> right = ExpectedEvents("bag_lz4.right");
  const std::vector<imu::ImuSample> imu = testing::ExpectedImu("bag_lz4");
  const std::vector<geometry::StampedPose> poses = testing::ExpectedPoses("bag_lz4");
  const auto dir = testing::ScratchDir();
  const std::string path = (dir / "out.bag").string();
  {
    auto writer = BagWriter::Create(
        path, {.compression = GetParam(), .chunk_bytes = 64 * 1024, .width = 240, .height = 180});
    ASSERT_TRUE(writer.ok()) << writer.status().message();
    std::size_t l = 0, r = 0, k = 0, q = 0;
    // Interleave the streams in 5 ms steps, as a simulator does.
    for (TimeNs t = left.front().t_ns; l < left.size() || r < right.size(); t += 5 * kNsPerMs) {
      std::size_t l_end = l, r_end = r;
      while (l_end < left.size() && left[l_end].t_ns < t)
        ++l_end;
      while (r_end < right.size() && right[r_end].t_ns < t)
        ++r_end;
      ASSERT_TRUE(
          (*writer)->WriteEvents("/davis/left/events", std::span(left).subspan(l, l_end - l)).ok());
      ASSERT_TRUE((*writer)
                      ->WriteEvents("/davis/right/events", std::span(right).subspan(r, r_end - r))
                      .ok());
      l = l_end;
      r = r_end;
      for (; k < imu.size() && imu[k].t_ns < t; ++k)
        ASSERT_TRUE((*writer)->WriteImu("/davis/left/imu", imu[k]).ok());
      for (; q < poses.size() && poses[q].t_ns < t; ++q)
        ASSERT_TRUE((*writer)->WritePose("/gt/pose", poses[q]).ok());
    }
    ASSERT_TRUE((*writer)->Close().ok());
  }
  for (auto [topic, expected] :
       {std::pair{"/davis/left/events", &left}, std::pair{"/davis/right/events", &right}}) {
    auto stream = BagEventStream::Open(path, topic, {});
    ASSERT_TRUE(stream.ok()) << stream.status().message();
    EXPECT_TRUE(testing::ReadAllOf(**stream, kNsPerMs) == *expected) << topic;
  }
  auto imu_stream = BagImuStream::Open(path, "", {});
  ASSERT_TRUE(imu_stream.ok());
  EXPECT_EQ(testing::ReadAllOf(**imu_stream, kNsPerMs).size(), imu.size());
  // python3-rosbag (independent reader): index, chunk infos, 1 ms packets, values.
  const std::string command = "/usr/bin/python3 " AAVIO_SOURCE_DIR "/tests/fixtures/check_bag.py " +
                              path + " " + testing::EventFixtureDir() + "/bag_lz4";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

INSTANTIATE_TEST_SUITE_P(Compressions, BagWriterTest,
                         ::testing::Values(BagCompression::kNone, BagCompression::kLz4,
                                           BagCompression::kBz2));

}  // namespace
}  // namespace aavio::io
