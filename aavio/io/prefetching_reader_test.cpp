#include "aavio/io/prefetching_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "tests/event_fixtures.hpp"

namespace aavio::io {
namespace {

using testing::Fixture;

SequenceDescription DsecPair(const std::string& left_file, const std::string& right_file) {
  SequenceDescription d;
  d.name = "pair";
  d.left = {SourceFormat::kDsecH5, Fixture(left_file), "", {}};
  d.right = {SourceFormat::kDsecH5, Fixture(right_file), "", {}};
  return d;
}

std::unique_ptr<SequenceReader> Open(const SequenceDescription& d) {
  Expected<std::unique_ptr<SequenceReader>> reader =
      SequenceReader::Open(d, {.packet_ns = 2 * kNsPerMs, .stream = {.width = 640, .height = 480}});
  EXPECT_TRUE(reader.ok()) << reader.status().message();
  return reader.ok() ? std::move(*reader) : nullptr;
}

bool SameEvents(const std::vector<events::Event>& a, const std::vector<events::Event>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].t_ns != b[i].t_ns || a[i].x != b[i].x || a[i].y != b[i].y ||
        a[i].polarity != b[i].polarity) {
      return false;
    }
  }
  return true;
}

// The packets, whatever bounds the read-ahead: a few packets, or one event (each packet read
// fills it, so the reader waits for every one to be taken).
class PrefetchingReaderBounds
    : public ::testing::TestWithParam<std::pair<std::size_t, std::size_t>> {};
INSTANTIATE_TEST_SUITE_P(Bounds, PrefetchingReaderBounds,
                         ::testing::Values(std::pair<std::size_t, std::size_t>{3, 4'000'000},
                                           std::pair<std::size_t, std::size_t>{100, 1}));

TEST_P(PrefetchingReaderBounds, DeliversExactlyThePacketsOfTheReader) {
  const SequenceDescription d = DsecPair("dsec_blosc.h5", "uncompressed.h5");
  auto direct = Open(d), behind = Open(d);
  ASSERT_TRUE(direct && behind);
  PrefetchingReader prefetching(behind.get(), GetParam().first, GetParam().second);
  std::size_t packets = 0, events = 0;
  while (true) {
    SensorPacket a, b;
    Expected<bool> more_a = direct->Next(&a);
    Expected<bool> more_b = prefetching.Next(&b);
    ASSERT_TRUE(more_a.ok() && more_b.ok());
    ASSERT_EQ(*more_a, *more_b) << "after " << packets << " packets";
    if (!*more_a) break;
    ASSERT_EQ(a.t_begin_ns, b.t_begin_ns);
    ASSERT_EQ(a.t_end_ns, b.t_end_ns);
    ASSERT_TRUE(SameEvents(a.left, b.left) && SameEvents(a.right, b.right)) << packets;
    ++packets;
    events += b.left.size() + b.right.size();
  }
  EXPECT_GT(packets, 10u);
  EXPECT_GT(events, 1000u);
  SensorPacket after;
  Expected<bool> again = prefetching.Next(&after);  // the end stays the end
  ASSERT_TRUE(again.ok());
  EXPECT_FALSE(*again);
}

TEST(PrefetchingReader, PassesOnTheReadersErrorAfterTheGoodPackets) {
  auto reader = Open(DsecPair("corrupt.h5", "dsec_blosc.h5"));
  ASSERT_TRUE(reader);
  PrefetchingReader prefetching(reader.get(), 2);
  Status error;
  for (int i = 0; i < 1'000'000 && error.ok(); ++i) {
    SensorPacket packet;
    Expected<bool> more = prefetching.Next(&packet);
    if (!more.ok())
      error = more.status();
    else
      ASSERT_TRUE(*more) << "ended without the corruption's error";
  }
  EXPECT_NE(error.message().find("corrupt.h5"), std::string::npos) << error.message();
  EXPECT_NE(error.message().find("truncated or corrupt"), std::string::npos) << error.message();
  SensorPacket packet;
  EXPECT_FALSE(prefetching.Next(&packet).ok());  // and stays
}

// The read-ahead stops at its bound of events (the last packet read may pass it), however many
// packets it may hold, and once full waits for half of it to be taken before reading on.
TEST(PrefetchingReader, ReadsAheadNoFurtherThanItsBoundOfEvents) {
  const SequenceDescription d = DsecPair("dsec_blosc.h5", "uncompressed.h5");
  std::size_t largest = 0, total = 0;  // events in a packet, in the sequence
  {
    auto direct = Open(d);
    ASSERT_TRUE(direct);
    SensorPacket p;
    while (*direct->Next(&p)) {
      largest = std::max(largest, p.left.size() + p.right.size());
      total += p.left.size() + p.right.size();
    }
  }
  const std::size_t bound = total / 4;
  ASSERT_GT(bound, 2 * largest);  // room for several packets under the bound
  auto reader = Open(d);
  ASSERT_TRUE(reader);
  PrefetchingReader prefetching(reader.get(), 100'000, bound);
  auto settled = [&] {  // the reading thread filled up (or the test gives up after 10 s)
    PrefetchingReader::Buffered b, last;
    for (int i = 0; i < 1000; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      b = prefetching.buffered();
      if (b.events >= bound && b.packets == last.packets) break;
      last = b;
    }
    return b;
  };
  const PrefetchingReader::Buffered full = settled();
  EXPECT_GE(full.events, bound);
  EXPECT_LT(full.events, bound + largest);
  // Taking a quarter of it leaves the reader waiting; taking past half lets it fill up again.
  SensorPacket packet;
  std::size_t taken = 0;
  while (taken < full.events / 4) {
    ASSERT_TRUE(*prefetching.Next(&packet));
    taken += packet.left.size() + packet.right.size();
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(prefetching.buffered().events, full.events - taken);
  while (prefetching.buffered().events > bound / 2)
    ASSERT_TRUE(*prefetching.Next(&packet));
  const PrefetchingReader::Buffered again = settled();
  EXPECT_GE(again.events, bound);
  EXPECT_LT(again.events, bound + largest);
}

TEST(PrefetchingReader, StopsWhenDestroyedEarly) {
  auto reader = Open(DsecPair("dsec_blosc.h5", "uncompressed.h5"));
  ASSERT_TRUE(reader);
  {
    PrefetchingReader prefetching(reader.get(), 2);
    SensorPacket packet;
    ASSERT_TRUE(prefetching.Next(&packet).ok());
  }  // joins its thread with packets still unread: no hang, no crash
  SensorPacket packet;
  EXPECT_TRUE(reader->Next(&packet).ok());  // the reader itself is still usable
}

}  // namespace
}  // namespace aavio::io
