#include "aavio/events/events_config.hpp"

namespace aavio::events {

Status TimeSurfaceConfig::Validate() const {
  FieldChecker check;
  check.InRange("rate_hz", rate_hz, 1.0, 2000.0).InRange("decay_ms", decay_ms, 0.1, 10000.0);
  return check.status();
}

Status AdaptiveAccumulationConfig::Validate() const {
  FieldChecker check;
  check.InRange("grid_cols", grid_cols, 1, 256)
      .InRange("grid_rows", grid_rows, 1, 256)
      .Positive("check_interval_ms", check_interval_ms)
      .Positive("contrast_threshold", contrast_threshold)
      .Positive("window_ms", window_ms)
      .Require(check_interval_ms <= window_ms, "check_interval_ms",
               "must not exceed window_ms (" + FieldChecker::Num(window_ms) + ")")
      .InRange("map_count_gain", map_count_gain, 0, 255);
  return check.status();
}

Status EdgeSamplingConfig::Validate() const {
  FieldChecker check;
  check.InRange("num_points", num_points, 1, 1000000)
      .InRange("grid_cols", grid_cols, 1, 256)
      .InRange("grid_rows", grid_rows, 1, 256)
      .InRange("min_spacing_px", min_spacing_px, 0, 16);
  return check.status();
}

}  // namespace aavio::events
