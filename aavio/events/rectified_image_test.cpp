#include "aavio/events/rectified_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/fixtures/cameras.hpp"

namespace aavio::events {
namespace {

// Exact bilinear interpolation at (x, y) with zeros outside the image (cv::BORDER_CONSTANT).
double Bilinear(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int xi, int yi) {
    if (xi < 0 || yi < 0 || xi >= image.cols || yi >= image.rows) return 0.0;
    return static_cast<double>(image.at<std::uint8_t>(yi, xi));
  };
  return (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) +
         (1 - fx) * fy * at(x0, y0 + 1) + fx * fy * at(x0 + 1, y0 + 1);
}

// On every real camera (strong and mild radtan, equidistant): within ~1 level of exact bilinear
// interpolation (7-bit weights), within the quantisation of cv::remap (5-bit) of OpenCV, and the
// padded path gives the same bytes.
TEST(ImageRectifier, AgreesWithOpenCvRemapOnRealCameras) {
  for (const testing::RealCamera& camera : testing::AllRealCameras()) {
    const geometry::RectificationMaps maps =
        geometry::BuildRectificationMaps(camera.Model(), camera.R_rect, camera.P);
    cv::Mat raw(camera.raw.height, camera.raw.width, CV_8UC1);
    cv::randu(raw, 0, 256);
    cv::GaussianBlur(raw, raw, cv::Size(5, 5), 1.5);  // TS-like smoothness plus sharp zeros
    raw.rowRange(0, raw.rows / 3).setTo(0);
    const ImageRectifier rectifier(maps);
    cv::Mat ours, opencv, diff;
    rectifier.Rectify(raw, &ours);
    double worst = 0.0;
    for (int v = 0; v < raw.rows; ++v) {
      for (int u = 0; u < raw.cols; ++u) {
        const double x = maps.remap_x.at<float>(v, u), y = maps.remap_y.at<float>(v, u);
        const double exact = std::isfinite(x) && std::isfinite(y) ? Bilinear(raw, x, y) : 0.0;
        worst = std::max(worst, std::abs(ours.at<std::uint8_t>(v, u) - exact));
      }
    }
    EXPECT_LE(worst, 1.25) << camera.name;  // ½ level of rounding + ¹⁄₂₅₆ px on a 0→170 step
    cv::remap(raw, opencv, maps.remap_x, maps.remap_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
    cv::absdiff(ours, opencv, diff);
    double max_diff = 0.0;
    cv::minMaxLoc(diff, nullptr, &max_diff);
    EXPECT_LE(max_diff, 4.0) << camera.name;
    // The padded path gives the same bytes.
    cv::Mat padded = rectifier.MakePadded(), again;
    cv::Mat interior = ImageRectifier::PaddedInterior(padded);
    raw.copyTo(interior);
    rectifier.RectifyPadded(padded, &again);
    EXPECT_EQ(cv::norm(again, ours, cv::NORM_INF), 0.0) << camera.name;
  }
}

}  // namespace
}  // namespace aavio::events
