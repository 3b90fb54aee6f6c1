#pragma once
/// Moves raw-coordinate images (time surfaces, AA maps) to the rectified plane, once per image
/// (algorithm.md §1.4, "image content pipeline"): bilinear cv::remap with the camera's maps,
/// converted once to OpenCV's fixed-point form (faster, and the same bits on every run).

#include <opencv2/core/mat.hpp>

#include "aavio/geometry/rectification.hpp"

namespace aavio::events {

class ImageRectifier {
 public:
  explicit ImageRectifier(const geometry::RectificationMaps& maps);

  /// Bilinear remap of a raw CV_8UC1 image into the rectified plane; 0 outside the sensor.
  void Rectify(const cv::Mat& raw, cv::Mat* rectified) const;

  const cv::Mat& valid_mask() const { return valid_mask_; }

 private:
  cv::Mat map_xy_;      // CV_16SC2 integer positions
  cv::Mat map_frac_;    // CV_16UC1 interpolation table indices
  cv::Mat valid_mask_;  // CV_8UC1, 255 where the rectified pixel sees the sensor
};

}  // namespace aavio::events
