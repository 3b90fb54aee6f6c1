#include "aavio/io/streams.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace aavio::io {
namespace {

events::Event At(TimeNs t) {
  return {t, 1, 2, 1};
}

TEST(ReorderBuffer, ReleasesInTimeOrderOnceTheWindowHasPassed) {
  ReorderBuffer<events::Event> buffer(10);
  for (TimeNs t : {100, 105, 103, 110, 104, 120})
    ASSERT_TRUE(buffer.Push(At(t), "f").ok());
  EXPECT_FALSE(buffer.CanRelease(111));  // needs an element at >= 121
  EXPECT_TRUE(buffer.CanRelease(110));
  std::vector<events::Event> out;
  buffer.Release(110, &out);
  ASSERT_EQ(out.size(), 4u);  // 100, 103, 104, 105: strictly before 110
  for (std::size_t i = 1; i < out.size(); ++i)
    EXPECT_LE(out[i - 1].t_ns, out[i].t_ns);
  EXPECT_EQ(out.back().t_ns, 105);
  EXPECT_EQ(buffer.size(), 2u);  // 110 and 120 are held
  out.clear();
  buffer.Release(1000, &out);
  EXPECT_EQ(out.size(), 2u);
  EXPECT_EQ(buffer.size(), 0u);
}

TEST(ReorderBuffer, ReadingUntilTheEndOfTimeIsDefined) {
  // A reader asked for everything (t_end = INT64_MAX) adds its window to it: saturated, not an
  // overflow (found by the text fuzz target under UBSan).
  ReorderBuffer<events::Event> buffer(10 * kNsPerMs);
  ASSERT_TRUE(buffer.Push(At(5), "").ok());
  EXPECT_FALSE(buffer.CanRelease(std::numeric_limits<TimeNs>::max()));
  ASSERT_TRUE(buffer.Push(At(std::numeric_limits<TimeNs>::max()), "").ok());
  EXPECT_TRUE(buffer.CanRelease(std::numeric_limits<TimeNs>::max()));
}

TEST(ReorderBuffer, RefusesJumpsBackBeyondTheWindow) {
  ReorderBuffer<events::Event> buffer(10);
  ASSERT_TRUE(buffer.Push(At(100), "file.h5: event 0").ok());
  ASSERT_TRUE(buffer.Push(At(90), "file.h5: event 1").ok());  // exactly the window
  Status s = buffer.Push(At(89), "file.h5: event 2");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("file.h5: event 2: timestamp"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("reorder window"), std::string::npos);
}

TEST(ReorderBuffer, StampsAcrossTheWholeRangeAreRefusedWithoutOverflow) {
  // A corrupt file: an event at +1.7e18 ns, then one near the most negative stamp.
  ReorderBuffer<events::Event> buffer(10);
  ASSERT_TRUE(buffer.Push(At(1744227144742719000), "f: event 0").ok());
  const Status s = buffer.Push(At(-7479312017869478760), "f: event 1");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("reorder window"), std::string::npos) << s.message();
  ReorderBuffer<events::Event> low(std::numeric_limits<TimeNs>::max());
  ASSERT_TRUE(low.Push(At(std::numeric_limits<TimeNs>::max()), "f").ok());
  EXPECT_TRUE(low.Push(At(0), "f").ok());    // exactly the window back
  EXPECT_FALSE(low.Push(At(-1), "f").ok());  // a nanosecond beyond it
}

TEST(ReorderBuffer, RefusesElementsOlderThanWhatWasReleased) {
  ReorderBuffer<events::Event> buffer(10);
  ASSERT_TRUE(buffer.Push(At(100), "f").ok());
  std::vector<events::Event> out;
  buffer.Release(200, &out);
  EXPECT_FALSE(buffer.Push(At(150), "f").ok());
}

TEST(ReorderBuffer, AppendsInOrderRunsAndStopsWherePushMustDecide) {
  ReorderBuffer<events::Event> buffer(10);
  const std::vector<events::Event> block = {At(100), At(101), At(101), At(105), At(103), At(106)};
  EXPECT_EQ(buffer.AppendInOrder(block), 0u);  // nothing pushed yet: the first goes through Push
  ASSERT_TRUE(buffer.Push(block[0], "f").ok());
  const std::span<const events::Event> rest(block.data() + 1, block.size() - 1);
  EXPECT_EQ(buffer.AppendInOrder(rest), 3u);             // 101, 101, 105; 103 is out of order
  ASSERT_TRUE(buffer.Push(block[4], "f").ok());          // within the window: reordered
  EXPECT_EQ(buffer.AppendInOrder(rest.subspan(4)), 1u);  // 106 after the newest (105)
  std::vector<events::Event> out;
  buffer.Release(1000, &out);
  ASSERT_EQ(out.size(), block.size());
  for (std::size_t i = 1; i < out.size(); ++i)
    EXPECT_LE(out[i - 1].t_ns, out[i].t_ns);
  // Nothing older than what was released is appended.
  const std::vector<events::Event> late = {At(900), At(1001)};
  EXPECT_EQ(buffer.AppendInOrder(late), 0u);
  EXPECT_FALSE(buffer.Push(late[0], "f").ok());
}

TEST(ReorderBuffer, ResetDropsEverythingBeforeTheFloor) {
  ReorderBuffer<events::Event> buffer(10);
  ASSERT_TRUE(buffer.Push(At(100), "f").ok());
  buffer.Reset(500);
  ASSERT_TRUE(buffer.Push(At(400), "f").ok());  // silently dropped: before the seek target
  ASSERT_TRUE(buffer.Push(At(600), "f").ok());
  std::vector<events::Event> out;
  buffer.Release(1000, &out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].t_ns, 600);
}

TEST(ReorderBuffer, StaysSmallWhileStreaming) {
  ReorderBuffer<events::Event> buffer(kNsPerMs);
  std::vector<events::Event> out;
  for (TimeNs t = 0; t < 1'000'000; ++t) {
    ASSERT_TRUE(buffer.Push(At(t * 1000), "f").ok());
    if (t % 1000 == 999) {
      out.clear();
      buffer.Release(t * 1000 - kNsPerMs, &out);
      EXPECT_LE(buffer.size(), 2001u);
    }
  }
}

}  // namespace
}  // namespace aavio::io
