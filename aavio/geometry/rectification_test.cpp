#include "aavio/geometry/rectification.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "tests/fixtures/cameras.hpp"

namespace aavio::geometry {
namespace {

class RectificationTest : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    const testing::RealCamera c = testing::AllRealCameras()[GetParam()];
    camera_ = std::make_unique<CameraModel>(c.Model());
    R_ = c.R_rect;
    P_ = c.P;
    maps_ = BuildRectificationMaps(*camera_, R_, P_);
    cv::eigen2cv(Eigen::Matrix3d(R_), R_cv_);
    cv::eigen2cv(Eigen::Matrix<double, 3, 4>(P_), P_cv_);
    const CameraIntrinsics& in = camera_->intrinsics();
    K_cv_ = (cv::Mat_<double>(3, 3) << in.fx, 0, in.cx, 0, in.fy, in.cy, 0, 0, 1);
    D_cv_ = cv::Mat(in.coeffs, true).reshape(1, 1);
    if (in.model == DistortionModel::kEquidistant) D_cv_ = D_cv_.colRange(0, 4).clone();
  }
  bool fisheye() const { return camera_->model() == DistortionModel::kEquidistant; }

  std::unique_ptr<CameraModel> camera_;
  Eigen::Matrix3d R_;
  ProjectionMatrix P_;
  RectificationMaps maps_;
  cv::Mat R_cv_, P_cv_, K_cv_, D_cv_;
};

// The event look-up table equals OpenCV's (fisheye::)undistortPoints with R and P, iterated to
// convergence (the default 5 iterations of cv::undistortPoints are not enough for rpg's lens).
TEST_P(RectificationTest, EventLutAgreesWithOpenCvUndistortPoints) {
  std::vector<cv::Point2f> raw;
  for (int y = 0; y < camera_->height(); ++y) {
    for (int x = 0; x < camera_->width(); ++x)
      raw.emplace_back(x, y);
  }
  std::vector<cv::Point2f> expected;
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 1000, 1e-12);
  if (fisheye()) {
    cv::fisheye::undistortPoints(raw, expected, K_cv_, D_cv_, R_cv_, P_cv_, criteria);
  } else {
    cv::undistortPoints(raw, expected, K_cv_, D_cv_, R_cv_, P_cv_, criteria);
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const Eigen::Vector2f ours =
        maps_.RectifyPixel(static_cast<int>(raw[i].x), static_cast<int>(raw[i].y));
    ASSERT_TRUE(ours.allFinite()) << raw[i];
    worst = std::max(
        worst, static_cast<double>((ours - Eigen::Vector2f(expected[i].x, expected[i].y)).norm()));
  }
  EXPECT_LT(worst, 0.01) << testing::AllRealCameras()[GetParam()].name;
  RecordProperty("max_lut_difference_px", std::to_string(worst));
}

TEST_P(RectificationTest, RemapMapsAgreeWithOpenCvInitUndistortRectifyMap) {
  cv::Mat map_x, map_y;
  const cv::Size size(camera_->width(), camera_->height());
  if (fisheye()) {
    cv::fisheye::initUndistortRectifyMap(K_cv_, D_cv_, R_cv_, P_cv_, size, CV_32FC1, map_x, map_y);
  } else {
    cv::initUndistortRectifyMap(K_cv_, D_cv_, R_cv_, P_cv_, size, CV_32FC1, map_x, map_y);
  }
  double worst = 0.0;
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      const double dx = maps_.remap_x.at<float>(v, u) - map_x.at<float>(v, u);
      const double dy = maps_.remap_y.at<float>(v, u) - map_y.at<float>(v, u);
      worst = std::max(worst, std::hypot(dx, dy));
    }
  }
  EXPECT_LT(worst, 0.01) << testing::AllRealCameras()[GetParam()].name;
}

// The LUT and the remap maps are inverse to each other.
TEST_P(RectificationTest, LutAndRemapAreInverse) {
  double worst = 0.0;
  for (int y = 2; y < camera_->height() - 2; y += 3) {
    for (int x = 2; x < camera_->width() - 2; x += 3) {
      const Eigen::Vector2f r = maps_.RectifyPixel(x, y);
      const int u = static_cast<int>(std::lround(r.x()));
      const int v = static_cast<int>(std::lround(r.y()));
      if (u < 0 || v < 0 || u >= camera_->width() || v >= camera_->height()) continue;
      // Map the rounded rectified pixel back and compare with x + (rounding offset) / scale.
      Eigen::Vector2d back;
      const Eigen::Vector3d ray =
          R_.transpose() * (P_.leftCols<3>().inverse() * Eigen::Vector3d(r.x(), r.y(), 1.0));
      ASSERT_TRUE(camera_->Project(ray, &back));
      worst = std::max(worst, (back - Eigen::Vector2d(x, y)).norm());
    }
  }
  EXPECT_LT(worst, 1e-3);
}

TEST_P(RectificationTest, ValidMaskMarksPixelsThatSeeTheSensor) {
  int valid = 0;
  int inconsistent = 0;
  const int w = camera_->width();
  const int h = camera_->height();
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const float x = maps_.remap_x.at<float>(v, u);
      const float y = maps_.remap_y.at<float>(v, u);
      const bool well_inside = x >= 0.5f && y >= 0.5f && x <= w - 1.5f && y <= h - 1.5f;
      const bool outside = x < -1.0f || y < -1.0f || x > w || y > h;
      if (maps_.IsValid(u, v)) ++valid;
      if ((well_inside && !maps_.IsValid(u, v)) || (outside && maps_.IsValid(u, v))) {
        ++inconsistent;
      }
    }
  }
  EXPECT_EQ(inconsistent, 0);
  EXPECT_GT(valid, w * h / 2);
}

// raw_valid marks exactly the raw pixels whose rectified position is inside the image (not
// negative) and rounds onto a valid pixel, and most raw pixels are usable.
TEST_P(RectificationTest, RawValidFollowsTheLutAndTheMask) {
  const int w = camera_->width(), h = camera_->height();
  int usable = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Eigen::Vector2f r = maps_.RectifyPixel(x, y);
      const long u = std::lround(r.x()), v = std::lround(r.y());
      const bool expected = std::isfinite(r.x()) && r.x() >= 0.0f && r.y() >= 0.0f && u < w &&
                            v < h && maps_.IsValid(static_cast<int>(u), static_cast<int>(v));
      EXPECT_EQ(maps_.raw_valid.at<std::uint8_t>(y, x) != 0, expected) << x << ", " << y;
      usable += expected ? 1 : 0;
    }
  }
  EXPECT_GT(usable, w * h * 3 / 4);
}

INSTANTIATE_TEST_SUITE_P(RealCalibrations, RectificationTest,
                         ::testing::Range(0, static_cast<int>(testing::AllRealCameras().size())),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return testing::AllRealCameras()[param.param].name;
                         });

}  // namespace
}  // namespace aavio::geometry
