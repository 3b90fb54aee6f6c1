#include "aavio/io/stream_stats.hpp"

#include <algorithm>

namespace aavio::io {

namespace {

constexpr TimeNs kWindowNs = 10 * kNsPerMs;

double Rate(std::int64_t count, TimeNs duration_ns) {
  return duration_ns > 0 ? static_cast<double>(count) / NsToSeconds(duration_ns) : 0.0;
}

}  // namespace

Expected<EventStats> ComputeEventStats(EventStream& stream) {
  EventStats stats;
  std::vector<events::Event> window;
  TimeNs t = stream.info().t_first_ns;
  bool first = true;
  std::int64_t steps_without_data = 0;
  while (!stream.AtEnd()) {
    window.clear();
    t += kWindowNs;
    AAVIO_RETURN_IF_ERROR(stream.ReadUntil(t, &window));
    if (window.empty()) {
      // Jump over gaps quickly: a long empty stretch is read in growing steps.
      if (++steps_without_data > 100) t += kWindowNs * steps_without_data;
      continue;
    }
    steps_without_data = 0;
    if (first) {
      stats.t_first_ns = window.front().t_ns;
      first = false;
    }
    stats.t_last_ns = window.back().t_ns;
    stats.count += static_cast<std::int64_t>(window.size());
    stats.peak_rate_hz =
        std::max(stats.peak_rate_hz, static_cast<double>(window.size()) / NsToSeconds(kWindowNs));
    for (const events::Event& e : window) {
      stats.max_x = std::max<int>(stats.max_x, e.x);
      stats.max_y = std::max<int>(stats.max_y, e.y);
    }
  }
  stats.mean_rate_hz = Rate(stats.count, stats.t_last_ns - stats.t_first_ns);
  return stats;
}

Expected<ImuStats> ComputeImuStats(ImuStream& stream) {
  ImuStats stats;
  std::vector<imu::ImuSample> samples;
  TimeNs t = stream.info().t_first_ns;
  while (!stream.AtEnd()) {
    samples.clear();
    t += kNsPerS;
    AAVIO_RETURN_IF_ERROR(stream.ReadUntil(t, &samples));
    if (samples.empty()) continue;
    if (stats.count == 0) stats.t_first_ns = samples.front().t_ns;
    stats.t_last_ns = samples.back().t_ns;
    stats.count += static_cast<std::int64_t>(samples.size());
  }
  stats.rate_hz = Rate(stats.count - 1, stats.t_last_ns - stats.t_first_ns);
  return stats;
}

}  // namespace aavio::io
