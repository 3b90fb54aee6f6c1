#include "aavio/events/event_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::events {

EventStatisticsAccumulator::EventStatisticsAccumulator(int width, int height,
                                                       TimeNs isolation_window_ns,
                                                       TimeNs passage_gap_ns)
    : width_(width), height_(height), window_ns_(isolation_window_ns), gap_ns_(passage_gap_ns) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  last_t_.assign(n, 0);
  count_.assign(n, 0);
  run_.assign(n, 0);
  passages_.assign(n, 0);
  passage_events_.assign(n, 0);
  last_polarity_.assign(n, 0);
  last_supported_.assign(n, 0);
}

void EventStatisticsAccumulator::Add(std::span<const Event> events) {
  for (const Event& e : events) {
    const int x = e.x, y = e.y;
    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x;
    if (events_ == 0) t_first_ns_ = e.t_ns;
    t_last_ns_ = std::max(t_last_ns_, e.t_ns);
    ++events_;
    on_ += e.polarity ? 1 : 0;

    // Support from the neighbours' latest events, and for them from this one.
    bool supported = false;
    for (int dy = -1; dy <= 1; ++dy) {
      const int ny = y + dy;
      if (ny < 0 || ny >= height_) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx;
        if ((dx == 0 && dy == 0) || nx < 0 || nx >= width_) continue;
        const std::size_t j = static_cast<std::size_t>(ny) * static_cast<std::size_t>(width_) + nx;
        if (count_[j] > 0 && e.t_ns - last_t_[j] <= window_ns_) {
          supported = true;
          last_supported_[j] = 1;
        }
      }
    }

    if (count_[i] > 0) {
      isolated_ += last_supported_[i] ? 0 : 1;  // the pixel's previous event is final now
      const TimeNs interval = std::max<TimeNs>(e.t_ns - last_t_[i], 0);
      const double us = std::max(static_cast<double>(interval) * 1e-3, 1.0);
      const int bin = std::min(kBins - 1, static_cast<int>(std::log10(us) * kBinsPerDecade));
      ++interval_histogram_[static_cast<std::size_t>(bin)];
      if (e.polarity == last_polarity_[i] && interval <= gap_ns_) {
        ++run_[i];
      } else {
        ++passages_[i];
        passage_events_[i] += run_[i];
        run_[i] = 1;
      }
    } else {
      run_[i] = 1;
    }
    ++count_[i];
    last_t_[i] = e.t_ns;
    last_polarity_[i] = e.polarity;
    last_supported_[i] = supported ? 1 : 0;
  }
}

EventStatistics EventStatisticsAccumulator::Finish() const {
  EventStatistics s;
  s.events = events_;
  if (events_ == 0) return s;
  const double pixels = static_cast<double>(count_.size());
  s.duration_s = std::max(NsToSeconds(t_last_ns_ - t_first_ns_), 1e-6);
  s.rate_ev_s = static_cast<double>(events_) / s.duration_s;
  s.rate_ev_px_s = s.rate_ev_s / pixels;
  s.on_fraction = static_cast<double>(on_) / static_cast<double>(events_);

  std::int64_t isolated = isolated_, active = 0, hot_events = 0, passages = 0, passage_events = 0;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x;
      if (count_[i] == 0) continue;
      ++active;
      isolated += last_supported_[i] ? 0 : 1;
      double neighbours = 0.0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
          neighbours +=
              count_[static_cast<std::size_t>(ny) * static_cast<std::size_t>(width_) + nx];
          ++n;
        }
      }
      const bool hot = count_[i] >= 10 && count_[i] > 5.0 * std::max(1.0, neighbours / n);
      if (hot) {
        ++s.hot_pixels;
        hot_events += count_[i];
      } else {
        passages += passages_[i] + 1;  // the passage in progress ends with the recording
        passage_events += passage_events_[i] + run_[i];
      }
    }
  }
  s.active_pixel_share = static_cast<double>(active) / pixels;
  s.isolated_share = static_cast<double>(isolated) / static_cast<double>(events_);
  s.hot_pixel_share = static_cast<double>(s.hot_pixels) / pixels;
  s.hot_event_share = static_cast<double>(hot_events) / static_cast<double>(events_);
  s.rate_without_hot_ev_px_s = static_cast<double>(events_ - hot_events) / s.duration_s /
                               (pixels - static_cast<double>(s.hot_pixels));
  s.events_per_passage =
      passages > 0 ? static_cast<double>(passage_events) / static_cast<double>(passages) : 0.0;

  // Interval percentiles from the log histogram (bin centres).
  std::int64_t intervals = 0;
  for (std::int64_t c : interval_histogram_)
    intervals += c;
  auto percentile_us = [&](double q) {
    const double target = q * static_cast<double>(intervals);
    std::int64_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += interval_histogram_[static_cast<std::size_t>(b)];
      if (static_cast<double>(seen) >= target) return std::pow(10.0, (b + 0.5) / kBinsPerDecade);
    }
    return std::pow(10.0, static_cast<double>(kBins) / kBinsPerDecade);
  };
  if (intervals > 0) {
    s.interval_p01_us = percentile_us(0.01);
    s.interval_median_ms = percentile_us(0.5) * 1e-3;
  }
  return s;
}

}  // namespace aavio::events
