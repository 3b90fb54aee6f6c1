#include "aavio/config/scene_measurement.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "aavio/io/calibration.hpp"
#include "aavio/io/formats/text/text_streams.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::config {
namespace {

geometry::StereoRig RpgRig() {
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "left.yaml", testing::kRpgLeftYaml);
  testing::WriteFile(dir / "right.yaml", testing::kRpgRightYaml);
  Expected<io::LoadedCalibration> calibration = io::LoadCalibration(dir.string());
  EXPECT_TRUE(calibration.ok()) << calibration.status().message();
  return calibration->rig;
}

// One event every millisecond in each camera, the first at `first_ns`.
std::vector<events::Event> EveryMillisecond(TimeNs first_ns, TimeNs last_ns, std::uint16_t x) {
  std::vector<events::Event> events;
  for (TimeNs t = first_ns; t <= last_ns; t += kNsPerMs)
    events.push_back({t, static_cast<std::uint16_t>(x + (t / kNsPerMs) % 40),
                      static_cast<std::uint16_t>(40 + (t / kNsPerMs) % 100), 1});
  return events;
}

TEST(MeasureSceneDepth, AnEventOnAMeasuringInstantIsMeasuredWithItsWindowNotRefused) {
  // A camera starting at rest: its first events come exactly where the packets end (1 ms ones
  // from t = 0) and where the probe measures (every 0.3 s). Each packet holds the events before
  // its end, so an event at 0.3 or 0.6 s comes in the packet after the one ending there —
  // measuring once that one was read refused it as "arrived after the tick was built".
  const geometry::StereoRig rig = RpgRig();
  std::vector<events::Event> left = {{0, 10, 10, 0}};  // the clock's start
  for (const events::Event& e : EveryMillisecond(300 * kNsPerMs, 900 * kNsPerMs, 60))
    left.push_back(e);
  const std::vector<events::Event> right = EveryMillisecond(300 * kNsPerMs, 900 * kNsPerMs, 50);
  const auto dir = testing::ScratchDir();
  auto stream = [&](const char* name, const std::vector<events::Event>& events) {
    const std::string path = (dir / name).string();
    Expected<std::unique_ptr<io::TextEventWriter>> writer = io::TextEventWriter::Create(path);
    EXPECT_TRUE(writer.ok()) << writer.status().message();
    EXPECT_TRUE((*writer)->Write(events).ok());
    EXPECT_TRUE((*writer)->Close().ok());
    Expected<std::unique_ptr<io::TextEventStream>> opened =
        io::TextEventStream::Open(path, {.width = 240, .height = 180});
    EXPECT_TRUE(opened.ok()) << opened.status().message();
    return std::unique_ptr<io::EventStream>(std::move(*opened));
  };
  io::SequenceReader reader(stream("left.txt", left), stream("right.txt", right), nullptr,
                            {.packet_ns = kNsPerMs});
  // Measured at 0.3, 0.6 and 0.9 s (too few edges for a depth: the call goes on to the end).
  Expected<std::optional<pipeline::SceneDepth>> depth =
      MeasureSceneDepth(&reader, rig, 0, 900 * kNsPerMs);
  ASSERT_TRUE(depth.ok()) << depth.status().message();

  // The reader is back at the start.
  io::SensorPacket packet;
  Expected<bool> more = reader.Next(&packet);
  ASSERT_TRUE(more.ok() && *more);
  EXPECT_EQ(packet.t_begin_ns, 0);
  ASSERT_FALSE(packet.left.empty());
  EXPECT_EQ(packet.left.front().t_ns, 0);
}

}  // namespace
}  // namespace aavio::config
