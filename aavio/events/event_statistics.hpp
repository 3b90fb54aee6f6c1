#pragma once
/// What an event stream says about its sensor (`aavio info --stats`, and the simulator's report):
/// rate, ON/OFF balance, the share of isolated events (a noise proxy), same-pixel intervals,
/// hot pixels and the events each edge passage makes. One pass, in time order, memory per pixel
/// only, so it runs on recordings of any length.
///
/// Definitions (docs/simulator.md, "Real and simulated sensors"):
///   - isolated: no event at any of the 8 neighbouring pixels within ±isolation_window (the
///     background-activity test of noise filters); the neighbour checked is the latest one, so a
///     pixel firing twice within the window can hide a neighbour's support (rare);
///   - hot pixel: ≥ 10 events and more than 5 times the mean count of its 8 neighbours;
///   - edge passage: consecutive events of one pixel with the same polarity, each within
///     passage_gap of the previous (hot pixels left out).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/events/event.hpp"

namespace aavio::events {

struct EventStatistics {
  std::int64_t events = 0;
  double duration_s = 0.0;
  double rate_ev_s = 0.0;     ///< events / duration
  double rate_ev_px_s = 0.0;  ///< per pixel of the array
  double rate_without_hot_ev_px_s = 0.0;
  double on_fraction = 0.0;
  double active_pixel_share = 0.0;  ///< pixels with at least one event
  double isolated_share = 0.0;
  std::int64_t hot_pixels = 0;
  double hot_pixel_share = 0.0;  ///< of the array
  double hot_event_share = 0.0;  ///< of the events
  double interval_p01_us = 0.0;  ///< same-pixel inter-event interval, 1st percentile
  double interval_median_ms = 0.0;
  double events_per_passage = 0.0;  ///< mean over edge passages
};

class EventStatisticsAccumulator {
 public:
  EventStatisticsAccumulator(int width, int height, TimeNs isolation_window_ns = 5 * kNsPerMs,
                             TimeNs passage_gap_ns = 5 * kNsPerMs);
  /// Events in time order (small reversals are tolerated); coordinates inside the array.
  void Add(std::span<const Event> events);
  EventStatistics Finish() const;

 private:
  static constexpr int kBinsPerDecade = 20;
  static constexpr int kBins = 9 * kBinsPerDecade;  // 1 µs .. 10^9 µs

  int width_, height_;
  TimeNs window_ns_, gap_ns_;
  std::vector<TimeNs> last_t_;
  std::vector<std::int32_t> count_;
  std::vector<std::int32_t> run_;       // length of the passage in progress
  std::vector<std::int32_t> passages_;  // finished passages
  std::vector<std::int64_t> passage_events_;
  std::vector<std::uint8_t> last_polarity_;
  std::vector<std::uint8_t> last_supported_;
  std::array<std::int64_t, kBins> interval_histogram_{};
  std::int64_t events_ = 0, on_ = 0, isolated_ = 0;
  TimeNs t_first_ns_ = 0, t_last_ns_ = 0;
};

}  // namespace aavio::events
