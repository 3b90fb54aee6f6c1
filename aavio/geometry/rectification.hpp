#pragma once
/// Per-camera rectification products (docs/conventions.md):
///   event_lut   raw integer pixel (x, y) → rectified sub-pixel (u, v), for events and samples;
///   remap_x/y   rectified pixel → raw sub-pixel, for cv::remap of whole images (bilinear);
///   raw_valid   raw pixels whose rectified position is a valid pixel (for events and samples);
///   valid_mask  rectified pixels whose bilinear footprint lies inside the raw image (255) or not
///               (0): the all-ones image remapped with remap_x/y, thresholded at 0.999
///               (plumb_bob/none) or 0.1 (equidistant), as the reference implementations do.
/// Rectified images have the raw image's size.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "aavio/geometry/camera_model.hpp"
#include "aavio/geometry/stereo_rig.hpp"

namespace aavio::geometry {

struct RectificationMaps {
  cv::Mat event_lut;   ///< CV_32FC2, height × width; NaN where undistortion does not converge
  cv::Mat remap_x;     ///< CV_32FC1, height × width
  cv::Mat remap_y;     ///< CV_32FC1, height × width
  cv::Mat valid_mask;  ///< CV_8UC1, height × width, 0 or 255
  cv::Mat raw_valid;   ///< CV_8UC1 over raw pixels: 255 where event_lut lands (rounded) on a
                       ///< valid rectified pixel — the raw pixels mapping can use

  /// Rectified position of raw pixel (x, y); x, y must be inside the image.
  Eigen::Vector2f RectifyPixel(int x, int y) const {
    const cv::Vec2f& v = event_lut.at<cv::Vec2f>(y, x);
    return {v[0], v[1]};
  }
  bool IsValid(int u, int v) const { return valid_mask.at<std::uint8_t>(v, u) > 125; }
};

/// Builds the maps of one camera: raw model, its rectification rotation R_rect_raw and the
/// rectified projection P (only its 3×3 part matters here).
RectificationMaps BuildRectificationMaps(const CameraModel& raw, const Eigen::Matrix3d& R_rect_raw,
                                         const ProjectionMatrix& P);

struct StereoRectification {
  RectificationMaps left;
  RectificationMaps right;
};

StereoRectification BuildStereoRectification(const StereoRig& rig);

}  // namespace aavio::geometry
