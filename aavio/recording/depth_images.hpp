#pragma once
/// A local map as images: its disparity map (what a run's `depth/` holds and depth evaluation
/// scores) and a colour picture of its inverse depth (the ESVO papers' figures: red near, blue
/// far).

#include <opencv2/core/mat.hpp>

#include "aavio/mapping/local_map.hpp"
#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::recording {

/// Inverse depth as a colour (jet: red near, blue far) over [rho_min, rho_max]; BGR.
class InverseDepthColours {
 public:
  InverseDepthColours(double rho_min, double rho_max);
  cv::Vec3b operator()(double rho) const;

 private:
  double rho_min_, rho_max_;
  cv::Mat jet_;
};

/// CV_16UC1, disparity × 256 at each point's nearest pixel, 0 = none (DSEC's ground-truth
/// format; points outside the image or the 16-bit range are left out).
cv::Mat DisparityImage(const mapping::LocalMap& map, const mapping::RectifiedStereo& stereo);

/// The map's points as dots coloured by inverse depth (8-bit BGR), as the ESVO papers draw them:
/// over the time surface of the observation the map was made on (`time_surface`, CV_8UC1, in
/// grey), or on black where it is empty.
cv::Mat InverseDepthPicture(const mapping::LocalMap& map, int width, int height,
                            const InverseDepthColours& colours, const cv::Mat& time_surface = {});

}  // namespace aavio::recording
