#pragma once
/// Summary statistics of a stream, for `aavio info`: counts, time range, mean and peak rates.

#include "aavio/io/streams.hpp"

namespace aavio::io {

struct EventStats {
  std::int64_t count = 0;
  TimeNs t_first_ns = 0;
  TimeNs t_last_ns = 0;
  double mean_rate_hz = 0.0;  ///< count / duration
  double peak_rate_hz = 0.0;  ///< the busiest 10 ms window, per second
  int max_x = -1;             ///< largest coordinates seen (-1 when not scanned)
  int max_y = -1;
};

struct ImuStats {
  std::int64_t count = 0;
  TimeNs t_first_ns = 0;
  TimeNs t_last_ns = 0;
  double rate_hz = 0.0;  ///< (count − 1) / duration
};

/// One pass over the whole stream (from its current position to the end), decoding and checking
/// every element: a file that is corrupt, out of order or outside the sensor fails here.
Expected<EventStats> ComputeEventStats(EventStream& stream);
Expected<ImuStats> ComputeImuStats(ImuStream& stream);

}  // namespace aavio::io
