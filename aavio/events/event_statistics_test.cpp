#include "aavio/events/event_statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace aavio::events {
namespace {

Event E(double t_ms, int x, int y, int polarity = 1) {
  return {static_cast<TimeNs>(t_ms * 1e6), static_cast<std::uint16_t>(x),
          static_cast<std::uint16_t>(y), static_cast<std::uint8_t>(polarity)};
}

std::vector<Event> Sorted(std::vector<Event> events) {
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.t_ns < b.t_ns; });
  return events;
}

TEST(EventStatistics, IsolatedEventsHaveNoNeighbourWithinTheWindow) {
  EventStatisticsAccumulator acc(20, 20);
  // A lone event; a pair of neighbours 2 ms apart (both supported, in either order of support);
  // a neighbour that comes 8 ms later (both isolated).
  acc.Add(Sorted({E(0, 2, 2), E(1, 10, 10), E(3, 11, 11), E(20, 5, 15), E(28, 6, 15)}));
  const EventStatistics s = acc.Finish();
  EXPECT_EQ(s.events, 5);
  EXPECT_DOUBLE_EQ(s.isolated_share, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.on_fraction, 1.0);
  EXPECT_DOUBLE_EQ(s.active_pixel_share, 5.0 / 400.0);
}

TEST(EventStatistics, SamePixelIntervalsAndPassages) {
  EventStatisticsAccumulator acc(10, 10);
  std::vector<Event> events;
  // Pixel (1,1): passages of 3 ON events 0.1 ms apart every 50 ms, then 2 OFF ones.
  for (int k = 0; k < 20; ++k) {
    const double t0 = 50.0 * k;
    for (int j = 0; j < 3; ++j)
      events.push_back(E(t0 + 0.1 * j, 1, 1, 1));
    for (int j = 0; j < 2; ++j)
      events.push_back(E(t0 + 25.0 + 0.1 * j, 1, 1, 0));
  }
  acc.Add(events);
  const EventStatistics s = acc.Finish();
  EXPECT_EQ(s.hot_pixels, 1);  // it stands alone: hot by definition, left out of passages
  EventStatisticsAccumulator acc2(10, 10);
  // The same pixel with busy neighbours is not hot: passages count.
  std::vector<Event> with_neighbours = events;
  for (const Event& e : events) {
    with_neighbours.push_back({e.t_ns + 1000, 2, 1, e.polarity});
    with_neighbours.push_back({e.t_ns + 2000, 1, 2, e.polarity});
  }
  acc2.Add(Sorted(with_neighbours));
  const EventStatistics t = acc2.Finish();
  EXPECT_EQ(t.hot_pixels, 0);
  EXPECT_NEAR(t.events_per_passage, 2.5, 1e-9);
  EXPECT_DOUBLE_EQ(t.on_fraction, 0.6);
  // Intervals: 3 of every 5 are 0.1 ms, so the median is 0.1 ms (within a 20-per-decade bin).
  EXPECT_NEAR(t.interval_median_ms, 0.1, 0.01);
  EXPECT_NEAR(t.interval_p01_us, 100.0, 10.0);
  EXPECT_DOUBLE_EQ(t.isolated_share, 0.0);
}

TEST(EventStatistics, HotPixelsAndTheRateWithoutThem) {
  EventStatisticsAccumulator acc(100, 100);
  std::vector<Event> events;
  for (int k = 0; k < 1000; ++k)
    events.push_back(E(k, 50, 50));  // 1 kHz, 0 .. 999 ms: the recording lasts 0.999 s
  for (int k = 0; k < 100; ++k)
    events.push_back(E(10.0 * k + 0.5, k % 100, (k * 37) % 100 == 50 ? 51 : (k * 37) % 100));
  acc.Add(Sorted(events));
  const EventStatistics s = acc.Finish();
  EXPECT_EQ(s.hot_pixels, 1);
  EXPECT_NEAR(s.hot_event_share, 1000.0 / 1100.0, 1e-9);
  EXPECT_NEAR(s.rate_without_hot_ev_px_s, 100.0 / 0.999 / 9999.0, 1e-6);
  EXPECT_NEAR(s.rate_ev_s, 1100.0 / 0.999, 1e-6);
}

}  // namespace
}  // namespace aavio::events
