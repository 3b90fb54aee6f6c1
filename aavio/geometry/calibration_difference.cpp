#include "aavio/geometry/calibration_difference.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "aavio/common/format.hpp"

namespace aavio::geometry {
namespace {

constexpr int kColumns = 9, kRows = 7;

// A raw pixel of `camera` rectified by R_rect and P (its first three columns: a point at
// infinity); false when it does not undistort or lands behind the rectified camera.
bool Rectify(const CameraModel& camera, const Eigen::Matrix3d& R_rect, const ProjectionMatrix& P,
             const Eigen::Vector2d& raw, Eigen::Vector2d* rectified) {
  Eigen::Vector3d ray;
  if (!camera.Unproject(raw, &ray)) return false;
  const Eigen::Vector3d p = P.leftCols<3>() * (R_rect * ray);
  if (!(p.z() > 1e-9)) return false;
  *rectified = p.head<2>() / p.z();
  return true;
}

bool InView(const CameraModel& camera, const Eigen::Vector2d& pixel) {
  return pixel.x() >= 0.0 && pixel.y() >= 0.0 && pixel.x() <= camera.width() - 1.0 &&
         pixel.y() <= camera.height() - 1.0;
}

double Median(std::vector<double> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

Expected<CalibrationDifference> CompareCalibrations(const StereoRig& used, const StereoRig& truth) {
  if (used.width() != truth.width() || used.height() != truth.height()) {
    return InvalidArgument(StrFormat("the calibrations are of different sensors (%d×%d and %d×%d)",
                                     used.width(), used.height(), truth.width(), truth.height()));
  }
  const double predicted = used.cx_left() - used.cx_right();
  std::vector<double> disparities, rows;
  for (int j = 0; j < kRows; ++j) {
    for (int i = 0; i < kColumns; ++i) {
      // 10 % to 90 % of the view, where both cameras of a rig usually see.
      const double u = truth.width() * (0.1 + 0.8 * i / (kColumns - 1));
      const double v = truth.height() * (0.1 + 0.8 * j / (kRows - 1));
      const Eigen::Vector3d ray_rect((u - truth.cx_left()) / truth.focal_px(),
                                     (v - truth.cy()) / truth.focal_px(), 1.0);
      const Eigen::Vector3d ray_left = truth.R_rect_left_left().transpose() * ray_rect;
      const Eigen::Vector3d ray_right = truth.T_right_left().R * ray_left;
      Eigen::Vector2d raw_left, raw_right, left, right;
      if (!truth.left().Project(ray_left, &raw_left) ||
          !truth.right().Project(ray_right, &raw_right) || !InView(truth.left(), raw_left) ||
          !InView(truth.right(), raw_right) ||
          !Rectify(used.left(), used.R_rect_left_left(), used.P_left(), raw_left, &left) ||
          !Rectify(used.right(), used.R_rect_right_right(), used.P_right(), raw_right, &right)) {
        continue;
      }
      disparities.push_back(left.x() - right.x() - predicted);
      rows.push_back(left.y() - right.y());
    }
  }
  if (disparities.size() < kColumns * kRows / 4) {
    return InvalidArgument(StrFormat(
        "only %zu of %d directions are in both cameras' views: are the calibrations of one rig?",
        disparities.size(), kColumns * kRows));
  }
  CalibrationDifference d;
  d.directions = static_cast<int>(disparities.size());
  d.disparity_offset_px = Median(disparities);
  const auto [lo, hi] = std::minmax_element(disparities.begin(), disparities.end());
  d.disparity_offset_min_px = *lo;
  d.disparity_offset_max_px = *hi;
  d.row_offset_px = Median(rows);
  for (double r : rows)
    d.max_row_offset_px = std::max(d.max_row_offset_px, std::abs(r));
  d.fb_ratio = (used.focal_px() * used.baseline_m()) / (truth.focal_px() * truth.baseline_m());
  return d;
}

}  // namespace aavio::geometry
