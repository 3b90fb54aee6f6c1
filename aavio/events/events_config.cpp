#include "aavio/events/events_config.hpp"

namespace aavio::events {

Status TimeSurfaceConfig::Validate() const {
  FieldChecker check;
  check.InRange("rate_hz", rate_hz, 1.0, 2000.0)
      .InRange("decay_ms", decay_ms, 0.1, 10000.0)
      .InRange("median_half_size", median_half_size, 0, 5)
      .Require(gaussian_kernel >= 1 && gaussian_kernel <= 31 && gaussian_kernel % 2 == 1,
               "gaussian_kernel", "must be odd, from 1 to 31")
      .Require(offset_free_blur >= 1 && offset_free_blur <= 63 && offset_free_blur % 2 == 1,
               "offset_free_blur", "must be odd, from 1 to 63")
      .NonNegative("max_events_per_ms", max_events_per_ms);
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
      .Positive("activity_tolerance", activity_tolerance)
      .InRange("activity_check_events", activity_check_events, 1, 100000)
      .InRange("map_count_gain", map_count_gain, 0, 255);
  return check.status();
}

Status EdgeSamplingConfig::Validate() const {
  FieldChecker check;
  check.InRange("num_points", num_points, 1, 1000000)
      .InRange("grid_cols", grid_cols, 1, 256)
      .InRange("grid_rows", grid_rows, 1, 256)
      .InRange("proportional_share", proportional_share, 0.0, 1.0)
      .Require(block_cap_fraction > 0.0 && block_cap_fraction <= 1.0, "block_cap_fraction",
               "= " + FieldChecker::Num(block_cap_fraction) + " must be in (0, 1]")
      .InRange("min_spacing_px", min_spacing_px, 0, 16)
      .Positive("newest_window_ms", newest_window_ms);
  return check.status();
}

}  // namespace aavio::events
