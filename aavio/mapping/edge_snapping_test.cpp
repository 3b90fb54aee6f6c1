#include "aavio/mapping/edge_snapping.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace aavio::mapping {
namespace {

// A vertical edge moving right, newest at x = 30.4: the negative TS is dark there and brightens
// along the trail to the left (older events) and steeply to the right (no events yet), as an
// exponential decay leaves it.
cv::Mat MovingEdge(double edge_x) {
  cv::Mat ts(40, 60, CV_8UC1);
  for (int y = 0; y < ts.rows; ++y) {
    for (int x = 0; x < ts.cols; ++x) {
      const double d = x - edge_x;
      const double value =
          d >= 0 ? std::min(255.0, 20.0 + 120.0 * d) : std::min(255.0, 20.0 - 30.0 * d);
      ts.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::lround(value));
    }
  }
  return ts;
}

TEST(EdgeSnapping, TrailSamplesMoveOntoTheNewestEdge) {
  const cv::Mat ts = MovingEdge(30.4);
  cv::Mat ts_f, gu, gv;
  ts.convertTo(ts_f, CV_32F);
  cv::Sobel(ts_f, gu, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(ts_f, gv, CV_32F, 0, 1, 3, 1.0 / 8.0);
  std::vector<events::EdgeSample> samples = {
      {29, 20, 29.0f, 20.0f, 3},  // on the trail, 1.4 px behind
      {28, 10, 28.0f, 10.0f, 3},  // 2.4 px behind: beyond a 2 px reach, it moves 2 px
      {31, 15, 31.0f, 15.0f, 3},  // just ahead
  };
  const std::vector<events::EdgeSample> before = samples;
  SnapToNewestEdge(ts, gu, gv, 2.0, &samples);
  // (sampled on whole pixels, the valley's lowest pixel is x = 30: within half a pixel is all an
  // image can say)
  EXPECT_NEAR(samples[0].u, 30.4f, 0.5f);
  EXPECT_NEAR(samples[1].u, 30.0f, 0.05f);
  EXPECT_NEAR(samples[2].u, 30.4f, 0.5f);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    EXPECT_FLOAT_EQ(samples[i].v, before[i].v);  // along the gradient only
    EXPECT_EQ(samples[i].x, before[i].x);        // the raw pixel stays
  }
  // A flat surface leaves samples where they are; a zero reach changes nothing.
  const cv::Mat flat(40, 60, CV_8UC1, cv::Scalar(128));
  const cv::Mat zero = cv::Mat::zeros(40, 60, CV_32FC1);
  std::vector<events::EdgeSample> still = before;
  SnapToNewestEdge(flat, zero, zero, 2.0, &still);
  EXPECT_FLOAT_EQ(still[0].u, 29.0f);
  SnapToNewestEdge(ts, gu, gv, 0.0, &still);
  EXPECT_FLOAT_EQ(still[1].u, 28.0f);
}

}  // namespace
}  // namespace aavio::mapping
