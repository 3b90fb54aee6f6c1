#include "aavio/mapping/mapping_config.hpp"

#include "aavio/common/format.hpp"

namespace aavio::mapping {

Status StaticStereoConfig::Validate() const {
  FieldChecker check;
  check
      .Require(zncc_threshold > 0.0 && zncc_threshold <= 1.0, "zncc_threshold",
               "= " + FieldChecker::Num(zncc_threshold) + " must be in (0, 1] (cost ½(1 − ZNCC))")
      .InRange("uniqueness", uniqueness, 0.0, 1.0)
      .InRange("left_right_tolerance_px", left_right_tolerance_px, -1, 100)
      .InRange("out_of_view_radius_px", out_of_view_radius_px, 0, 50);
  return check.status();
}

Status TemporalStereoConfig::Validate() const {
  FieldChecker check;
  check.Positive("min_translation_m", min_translation_m)
      .NonNegative("min_parallax_px", min_parallax_px)
      .NonNegative("max_relative_depth_error", max_relative_depth_error)
      .NonNegative("cross_check_px", cross_check_px)
      .NonNegative("residual_threshold", residual_threshold)
      .NonNegative("max_inv_depth_stddev", max_inv_depth_stddev)
      .Positive("min_depth_m", min_depth_m)
      .Require(max_depth_m > min_depth_m, "max_depth_m",
               "= " + FieldChecker::Num(max_depth_m) + " must exceed min_depth_m (" +
                   FieldChecker::Num(min_depth_m) + ")");
  return check.status();
}

Status DepthRefinementConfig::Validate() const {
  FieldChecker check;
  check
      .Require(
          student_t_nu > 2.0 && student_t_nu < 1000.0, "student_t_nu",
          "= " + FieldChecker::Num(student_t_nu) + " must be in (2, 1000): ν ≤ 2 has no variance")
      .Positive("student_t_scale", student_t_scale)
      .Positive("residual_threshold", residual_threshold)
      .Positive("max_inv_depth_stddev", max_inv_depth_stddev)
      .NonNegative("max_relative_stddev", max_relative_stddev);
  return check.status();
}

Status FusionConfig::Validate() const {
  FieldChecker check;
  check.InRange("max_frames", max_frames, 1, 1000)
      .InRange("max_points", max_points, 1, 10000000)
      .InRange("radius", radius, 0, 10);
  return check.status();
}

Status BootstrapConfig::Validate() const {
  FieldChecker check;
  check.InRange("min_points", min_points, 1, 10000000)
      .InRange("min_coverage", min_coverage, 0.0, 1.0);
  return check.status();
}

Status MappingConfig::Validate() const {
  FieldChecker check;
  check.InRange("rate_hz", rate_hz, 0.1, 1000.0)
      .Positive("inv_depth_min", inv_depth_min)
      .Require(inv_depth_max > inv_depth_min, "inv_depth_max",
               "= " + FieldChecker::Num(inv_depth_max) + " must exceed inv_depth_min (" +
                   FieldChecker::Num(inv_depth_min) + "); the depth range is [1/inv_depth_max, " +
                   "1/inv_depth_min] m")
      .InRange("max_points", max_points, 1, 1000000)
      .NonNegative("eta", eta)
      .InRange("snap_to_edge_px", snap_to_edge_px, 0.0, 5.0)
      .Nested("static_stereo", static_stereo)
      .Nested("temporal_stereo", temporal_stereo)
      .Nested("depth_refinement", depth_refinement)
      .Nested("fusion", fusion)
      .Nested("regularization", regularization)
      .Nested("bootstrap", bootstrap);
  return check.status();
}

std::string BootstrapConfig::Refusal(const char* stereo, std::size_t points, std::size_t matchable,
                                     std::size_t samples) const {
  return StrFormat(
      "%s bootstrap found %zu points at the %zu edge samples (%zu of them not along a "
      "near-horizontal edge): fewer than mapping.bootstrap.min_points = %d, and fewer than "
      "mapping.bootstrap.min_coverage = %g of those %zu or than %zu",
      stereo, points, samples, matchable, min_points, min_coverage, matchable,
      kMinRegistrationPoints);
}

}  // namespace aavio::mapping
