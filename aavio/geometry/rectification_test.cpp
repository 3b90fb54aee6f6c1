#include "aavio/geometry/rectification.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace aavio::geometry {
namespace {

struct Case {
  const char* name;
  CameraIntrinsics raw;
  double R_rect[9];
  double P[12];
};

// Left cameras of real calibrations: rpg (strong radtan), DSEC (radtan), MVSEC and TUM-VIE
// (equidistant), and the right camera of rpg (P with the −f·b column).
std::vector<Case> Cases() {
  return {
      {"rpg_left",
       {240,
        180,
        196.639,
        196.733,
        105.064,
        72.4717,
        DistortionModel::kRadtan,
        {-0.336733, 0.111789, -0.00140053, -0.000459594}},
       {0.999791, -0.018779, -0.00802416, 0.0187767, 0.999824, -0.000360707, 0.00802952,
        0.000209964, 0.999968},
       {156.925, 0, 108.167, 0, 0, 156.925, 78.4205, 0, 0, 0, 1, 0}},
      {"rpg_right",
       {240,
        180,
        196.426,
        196.564,
        110.745,
        88.1131,
        DistortionModel::kRadtan,
        {-0.346294, 0.12772, -0.000272051, -0.000195801}},
       {0.999589, 0.0222217, -0.0181009, -0.0222166, 0.999753, 0.000486491, 0.0181073, -8.41512e-05,
        0.999836},
       {156.925, 0, 108.167, -23.2327, 0, 156.925, 78.4205, 0, 0, 0, 1, 0}},
      {"dsec_left",
       {640,
        480,
        553.469,
        553.399,
        346.653,
        216.521,
        DistortionModel::kRadtan,
        {-0.0935648, 0.194458, 7.64243e-05, 0.00195639}},
       {0.999866, -0.00319364, 0.0160517, 0.00322964, 0.999992, -0.00221712, -0.0160445, 0.00226867,
        0.999869},
       {536.0578704071853, 0, 336.2674980163574, 0, 0, 536.0578704071853, 222.2888011932373, 0, 0,
        0, 1, 0}},
      {"mvsec_left",
       {346,
        260,
        226.38018519795807,
        226.15002947047415,
        173.6470807871759,
        133.73271487507847,
        DistortionModel::kEquidistant,
        {-0.048031442223833355, 0.011330957517194437, -0.055378166304281135, 0.021500973881459395}},
       {0.999877311526236, 0.015019439766575743, -0.004447282784398257, -0.014996983873604017,
        0.9998748347535599, 0.005040367172759556, 0.004522429630305261, -0.004973052949604937,
        0.9999774079320989},
       {199.6530123165822, 0, 177.43276376280926, 0, 0, 199.6530123165822, 126.81215684365904, 0, 0,
        0, 1, 0}},
      {"tumvie_left",
       {1280,
        720,
        1049.583,
        1049.423,
        634.7184,
        263.4698,
        DistortionModel::kEquidistant,
        {-0.1151966, -0.06222183, 0.2168261, -0.2352862}},
       {0.999754826676689, -0.01266626048306591, -0.01816183861944204, 0.01247096879510851,
        0.9998636259452682, -0.01082610035478137, 0.01829648802297759, 0.01059695036109404,
        0.9997764465964727},
       {974.8248485687409, 0, 657.1452947326158, 0, 0, 974.8248485687409, 249.0317449660879, 0, 0,
        0, 1, 0}},
  };
}

class RectificationTest : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    const Case c = Cases()[GetParam()];
    camera_ = std::make_unique<CameraModel>(*CameraModel::Create(c.raw));
    R_ = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(c.R_rect);
    P_ = Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(c.P);
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
  EXPECT_LT(worst, 0.01) << Cases()[GetParam()].name;
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
  EXPECT_LT(worst, 0.01) << Cases()[GetParam()].name;
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

INSTANTIATE_TEST_SUITE_P(RealCalibrations, RectificationTest, ::testing::Range(0, 5),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return std::string(Cases()[param.param].name);
                         });

}  // namespace
}  // namespace aavio::geometry
