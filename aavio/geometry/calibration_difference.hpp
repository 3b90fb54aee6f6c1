#pragma once
/// How far a stereo calibration is from the true one, in what the odometry sees: the disparity a
/// point at infinity gets, and the rows the two rectified images put it on. For a simulated twin
/// (which knows the calibration it was perturbed from) or a rig calibrated twice.
///
/// A point at infinity should have the disparity the calibration predicts for it (cx_left −
/// cx_right); any other is an offset that turns into a depth error growing with depth: a point at
/// depth z gets fb / (fb / z + ε), short by about ε·z / fb of its depth. A row difference makes
/// the stereo matching compare the wrong rows. Both vary over the view (a focal length error
/// scales one image about its centre), so they are given as the median and the extremes over a
/// grid of directions.

#include "aavio/common/status.hpp"
#include "aavio/geometry/stereo_rig.hpp"

namespace aavio::geometry {

struct CalibrationDifference {
  /// Disparity at infinity through `used` minus what `used` predicts for it [px]; > 0: depths
  /// too short.
  double disparity_offset_px = 0.0;  ///< median over the view
  double disparity_offset_min_px = 0.0, disparity_offset_max_px = 0.0;
  double row_offset_px = 0.0;      ///< median of left row − right row [px]
  double max_row_offset_px = 0.0;  ///< largest |left row − right row| [px]
  double fb_ratio = 1.0;           ///< f·b of `used` / f·b of `truth`
  int directions = 0;              ///< grid directions seen by both cameras of both rigs
};

/// Rays at infinity over a 9×7 grid of `truth`'s rectified left view, seen through `truth`'s raw
/// cameras and rectified with `used`. The rigs must have the same image size; an error when too
/// few directions are in both cameras' views.
Expected<CalibrationDifference> CompareCalibrations(const StereoRig& used, const StereoRig& truth);

}  // namespace aavio::geometry
