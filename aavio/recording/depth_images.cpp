#include "aavio/recording/depth_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

namespace aavio::recording {

InverseDepthColours::InverseDepthColours(double rho_min, double rho_max)
    : rho_min_(rho_min), rho_max_(rho_max) {
  cv::Mat level(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i)
    level.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
  cv::applyColorMap(level, jet_, cv::COLORMAP_JET);
}

cv::Vec3b InverseDepthColours::operator()(double rho) const {
  const double x = std::clamp((rho - rho_min_) / (rho_max_ - rho_min_), 0.0, 1.0);
  return jet_.at<cv::Vec3b>(0, static_cast<int>(std::lround(255.0 * x)));
}

cv::Mat DisparityImage(const mapping::LocalMap& map, const mapping::RectifiedStereo& stereo) {
  cv::Mat disparity(stereo.height, stereo.width, CV_16UC1, cv::Scalar(0));
  for (const mapping::DepthPoint& p : map.points) {
    const int u = static_cast<int>(std::lround(p.u)), v = static_cast<int>(std::lround(p.v));
    const double raw = std::round(256.0 * stereo.Disparity(p.rho));
    if (u >= 0 && v >= 0 && u < stereo.width && v < stereo.height && raw >= 1.0 && raw <= 65535.0)
      disparity.at<std::uint16_t>(v, u) = static_cast<std::uint16_t>(raw);
  }
  return disparity;
}

cv::Mat InverseDepthPicture(const mapping::LocalMap& map, int width, int height,
                            const InverseDepthColours& colours, const cv::Mat& time_surface) {
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(0, 0, 0));
  if (time_surface.type() == CV_8UC1 && time_surface.cols == width && time_surface.rows == height) {
    // Dimmed, so that the dots stand out of the bright recent edges.
    cv::Mat grey;
    time_surface.convertTo(grey, CV_8UC1, 0.6);
    cv::cvtColor(grey, image, cv::COLOR_GRAY2BGR);
  }
  for (const mapping::DepthPoint& p : map.points) {
    const cv::Vec3b c = colours(p.rho);
    cv::circle(image, {static_cast<int>(std::lround(p.u)), static_cast<int>(std::lround(p.v))}, 1,
               cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  return image;
}

}  // namespace aavio::recording
