#include "aavio/tracking/tracking_config.hpp"

namespace aavio::tracking {

Status TrackingConfig::Validate() const {
  FieldChecker check;
  check.InRange("max_points", max_points, 1, 1000000)
      .InRange("batch_size", batch_size, 1, 1000000)
      .Require(batch_size <= max_points, "batch_size",
               "must not exceed max_points (" + FieldChecker::Num(max_points) + ")")
      .InRange("min_map_points", min_map_points, 1, 1000000)
      .InRange("max_iterations", max_iterations, 1, 1000)
      .InRange("polish_iterations", polish_iterations, 0, 100)
      .Positive("huber_threshold", huber_threshold)
      .Positive("max_correction_deg", max_correction_deg)
      .Positive("max_correction_m", max_correction_m)
      .InRange("velocity_gain", velocity_gain, 0.0, 1.0)
      .InRange("lost_velocity_decay", lost_velocity_decay, 0.0, 1.0)
      .InRange("gyro_rotation_weight", gyro_rotation_weight, 0.0, 1e9)
      .InRange("translation_prior_weight", translation_prior_weight, 0.0, 1e9);
  return check.status();
}

}  // namespace aavio::tracking
