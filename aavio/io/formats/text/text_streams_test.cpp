#include "aavio/io/formats/text/text_streams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "tests/event_fixtures.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

using testing::Fixture;

TEST(TextStreams, ReadsEventsAsWritten) {
  const std::vector<events::Event> expected = testing::ExpectedEvents("events_txt");
  auto stream = TextEventStream::Open(Fixture("events.txt"), {.width = 240, .height = 180});
  ASSERT_TRUE(stream.ok()) << stream.status().message();
  EXPECT_EQ((*stream)->info().t_first_ns, expected.front().t_ns);
  EXPECT_EQ((*stream)->info().t_last_ns, expected.back().t_ns);
  EXPECT_TRUE(testing::ReadAllOf(**stream, 2 * kNsPerMs) == expected);
  // Seeking re-reads from the start.
  ASSERT_TRUE((*stream)->Seek(expected[2500].t_ns).ok());
  std::vector<events::Event> out;
  ASSERT_TRUE((*stream)->ReadUntil(expected[2500].t_ns + 1, &out).ok());
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.front(), expected[2500]);
}

TEST(TextStreams, ReadsEcdImu) {
  const std::vector<imu::ImuSample> expected = testing::ExpectedImu("imu_txt");
  auto stream = TextImuStream::Open(Fixture("imu.txt"), ImuTextLayout::kEcd, {});
  ASSERT_TRUE(stream.ok()) << stream.status().message();
  const std::vector<imu::ImuSample> got = testing::ReadAllOf(**stream, 10 * kNsPerMs);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t_ns, expected[i].t_ns);
    EXPECT_EQ(got[i].gyro_rad_s, expected[i].gyro_rad_s);  // %.17g round-trips exactly
    EXPECT_EQ(got[i].accel_m_s2, expected[i].accel_m_s2);
  }
}

TEST(TextStreams, ReadsTumVieImuLayout) {
  const std::string path = testing::WriteFile(testing::ScratchDir() / "imu_data.txt",
                                              "# t gx gy gz ax ay az\n"
                                              "1000 0.1 0.2 0.3 1 2 9.8\n"
                                              "6000 0.1 0.2 0.3 1 2 9.8 25.5\n");
  auto stream = TextImuStream::Open(path, ImuTextLayout::kTumVie, {});
  ASSERT_TRUE(stream.ok());
  const std::vector<imu::ImuSample> got = testing::ReadAllOf(**stream, kNsPerMs);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[1].t_ns, 6 * kNsPerMs);
  EXPECT_DOUBLE_EQ(got[0].gyro_rad_s.z(), 0.3);
  EXPECT_DOUBLE_EQ(got[0].accel_m_s2.z(), 9.8);

  // A time whose nanoseconds overflow (found by fuzzing under UBSan): an error, not UB.
  const std::string huge = testing::WriteFile(testing::ScratchDir() / "imu_data.txt",
                                              "1777777775555555555 0 0 0 0 0 9.8\n");
  auto bad = TextImuStream::Open(huge, ImuTextLayout::kTumVie, {});
  std::vector<imu::ImuSample> out;
  const Status s =
      bad.ok() ? (*bad)->ReadUntil(std::numeric_limits<TimeNs>::max(), &out) : bad.status();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("imu_data.txt:1: t_us = 1777777775555555555 is beyond what "
                             "nanoseconds hold"),
            std::string::npos)
      << s.message();
}

TEST(TextStreams, MalformedLinesNameFileAndLine) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"1.0 1 2 1\n1.1 1 2\n", "events.txt:2: expected 4 columns"},
      {"1.0 1 2 1\nx 1 2 1\n", "events.txt:2: 'x' is not a time"},
      {"1.0 1 -2 1\n", "events.txt:1: x and y must be integers from 0 to 65535"},
      {"1.0 1 2 7\n", "events.txt:1: polarity p = 7 is none of 0 or -1 (OFF) and 1 (ON)"},
      {"1.0 300 2 1\n", "events.txt:1: event at (300, 2) is outside the 240x180 sensor"},
      {"1.0 1 2 1\n0.5 1 2 1\n", "events.txt:2: timestamp 0.500000000 s goes back 500.000 ms"},
  };
  for (const Case& c : cases) {
    const std::string path = testing::WriteFile(testing::ScratchDir() / "events.txt", c.text);
    auto stream = TextEventStream::Open(path, {.width = 240, .height = 180});
    Status s = stream.status();
    std::vector<events::Event> out;
    while (s.ok() && !(*stream)->AtEnd())
      s = (*stream)->ReadUntil(10 * kNsPerS, &out);
    ASSERT_FALSE(s.ok()) << c.text;
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << s.message();
  }
  EXPECT_EQ(TextEventStream::Open("/nonexistent.txt", {}).status().code(), StatusCode::kNotFound);
}

TEST(TextStreams, EmptyFilesAreEmptyStreams) {
  for (const char* text : {"", "# only a header\n"}) {
    const std::string path = testing::WriteFile(testing::ScratchDir() / "events.txt", text);
    auto stream = TextEventStream::Open(path, {});
    ASSERT_TRUE(stream.ok()) << stream.status().message();
    std::vector<events::Event> out;
    ASSERT_TRUE((*stream)->ReadUntil(kNsPerS, &out).ok());
    EXPECT_TRUE(out.empty());
    EXPECT_TRUE((*stream)->AtEnd());
  }
}

TEST(TextStreams, WritersRoundTrip) {
  const std::vector<events::Event> expected = testing::ExpectedEvents("events_txt");
  const auto dir = testing::ScratchDir();
  {
    auto writer = TextEventWriter::Create((dir / "events.txt").string());
    ASSERT_TRUE(writer.ok());
    ASSERT_TRUE((*writer)->Write(expected).ok());
    ASSERT_TRUE((*writer)->Close().ok());
  }
  auto stream = TextEventStream::Open((dir / "events.txt").string(), {});
  ASSERT_TRUE(stream.ok());
  EXPECT_TRUE(testing::ReadAllOf(**stream, kNsPerMs) == expected);

  const std::vector<imu::ImuSample> imu = testing::ExpectedImu("imu_txt");
  ASSERT_TRUE(WriteImuText((dir / "imu.txt").string(), imu).ok());
  auto imu_stream = TextImuStream::Open((dir / "imu.txt").string(), ImuTextLayout::kEcd, {});
  ASSERT_TRUE(imu_stream.ok());
  const std::vector<imu::ImuSample> back = testing::ReadAllOf(**imu_stream, kNsPerMs);
  ASSERT_EQ(back.size(), imu.size());
  EXPECT_LT((back[7].gyro_rad_s - imu[7].gyro_rad_s).norm(), 1e-8);
}

}  // namespace
}  // namespace aavio::io
