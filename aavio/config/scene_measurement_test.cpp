#include "aavio/config/scene_measurement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "aavio/io/calibration.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::config {
namespace {

// Events held in memory, read as a file's would be.
class EventsInMemory : public io::EventStream {
 public:
  explicit EventsInMemory(std::vector<events::Event> events) : events_(std::move(events)) {
    info_.description = "events in memory";
    info_.count = static_cast<std::int64_t>(events_.size());
    info_.t_first_ns = events_.front().t_ns;
    info_.t_last_ns = events_.back().t_ns;
  }
  const io::StreamInfo& info() const override { return info_; }
  Status ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out) override {
    for (; next_ < events_.size() && events_[next_].t_ns < t_end_ns; ++next_)
      out->push_back(events_[next_]);
    return Status::Ok();
  }
  Status Seek(TimeNs t_ns) override {
    next_ = static_cast<std::size_t>(
        std::lower_bound(events_.begin(), events_.end(), t_ns,
                         [](const events::Event& e, TimeNs t) { return e.t_ns < t; }) -
        events_.begin());
    return Status::Ok();
  }
  bool AtEnd() const override { return next_ == events_.size(); }

 private:
  std::vector<events::Event> events_;
  io::StreamInfo info_;
  std::size_t next_ = 0;
};

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
  // its end, so the event at 0.3 s comes in the packet after the one ending there — measuring
  // once that one was read refused it as "arrived after the tick was built".
  const geometry::StereoRig rig = RpgRig();
  std::vector<events::Event> left = {{0, 10, 10, 0}};  // the clock's start
  for (const events::Event& e : EveryMillisecond(300 * kNsPerMs, 900 * kNsPerMs, 60))
    left.push_back(e);
  const std::vector<events::Event> right = EveryMillisecond(300 * kNsPerMs, 900 * kNsPerMs, 50);
  io::SequenceReader reader(std::make_unique<EventsInMemory>(left),
                            std::make_unique<EventsInMemory>(right), nullptr,
                            {.packet_ns = kNsPerMs});
  Expected<std::optional<pipeline::SceneDepth>> depth =
      MeasureSceneDepth(&reader, rig, reader.start_ns(), reader.end_ns());
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
