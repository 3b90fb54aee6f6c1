#include "aavio/geometry/camera_model.hpp"

#include <gtest/gtest.h>

#include <random>

#include "aavio/geometry/random_draws.hpp"
#include "tests/fixtures/cameras.hpp"

namespace aavio::geometry {
namespace {

class CameraModelTest : public ::testing::TestWithParam<int> {
 protected:
  CameraModel camera() const { return testing::AllRealCameras()[GetParam()].Model(); }
};

TEST_P(CameraModelTest, DistortionJacobianMatchesFiniteDifferences) {
  const CameraModel cam = camera();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d x = DrawYx(u, rng);
    Eigen::Matrix2d J;
    cam.Distort(x, &J);
    Eigen::Matrix2d numeric;
    const double h = 1e-7;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d d = Eigen::Vector2d::Unit(k) * h;
      numeric.col(k) = (cam.Distort(x + d) - cam.Distort(x - d)) / (2 * h);
    }
    EXPECT_LT((J - numeric).cwiseAbs().maxCoeff(), 1e-7) << x.transpose();
  }
}

TEST_P(CameraModelTest, ProjectionJacobianMatchesFiniteDifferences) {
  const CameraModel cam = camera();
  const Eigen::Vector3d p(0.4, -0.25, 1.7);
  Eigen::Vector2d pixel;
  Eigen::Matrix<double, 2, 3> J;
  ASSERT_TRUE(cam.Project(p, &pixel, &J));
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d d = Eigen::Vector3d::Unit(k) * 1e-6;
    Eigen::Vector2d plus, minus;
    ASSERT_TRUE(cam.Project(p + d, &plus));
    ASSERT_TRUE(cam.Project(p - d, &minus));
    EXPECT_LT(((plus - minus) / 2e-6 - J.col(k)).norm(), 1e-4);
  }
}

TEST_P(CameraModelTest, UnprojectInvertsProjectOverTheWholeImage) {
  const CameraModel cam = camera();
  double worst_px = 0.0;
  for (int v = 0; v < cam.height(); v += 7) {
    for (int u = 0; u < cam.width(); u += 7) {
      Eigen::Vector3d ray;
      ASSERT_TRUE(cam.Unproject(Eigen::Vector2d(u, v), &ray)) << u << "," << v;
      EXPECT_DOUBLE_EQ(ray.z(), 1.0);
      Eigen::Vector2d back;
      ASSERT_TRUE(cam.Project(ray * 3.0, &back));
      worst_px = std::max(worst_px, (back - Eigen::Vector2d(u, v)).norm());
    }
  }
  EXPECT_LT(worst_px, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(RealCalibrations, CameraModelTest,
                         ::testing::Range(0, static_cast<int>(testing::AllRealCameras().size())),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return testing::AllRealCameras()[param.param].name;
                         });

TEST(CameraModel, PointsBehindTheCameraDoNotProject) {
  const CameraModel cam = testing::RpgLeft().Model();
  Eigen::Vector2d pixel;
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(0, 0, -1), &pixel));
  EXPECT_FALSE(cam.Project(Eigen::Vector3d(1, 0, 0), &pixel));
}

TEST(CameraModel, UndistortReportsNonConvergence) {
  // r (1 − 0.5 r²) peaks at 0.544 for r = 0.816: a distorted radius beyond that has no preimage.
  // A 30×30 image keeps its corners (radius 0.42) inside the invertible part.
  const CameraModel cam = *CameraModel::Create(
      {30, 30, 50, 50, 15, 15, DistortionModel::kRadtan, {-0.5, 0.0, 0.0, 0.0}});
  Eigen::Vector2d xn;
  EXPECT_FALSE(cam.Undistort(Eigen::Vector2d(0.7, 0.0), &xn));
  EXPECT_TRUE(cam.Undistort(Eigen::Vector2d(0.4, 0.0), &xn));
}

TEST(CameraModel, CreateRejectsADistortionNoLensHas) {
  auto refused = [](int size, std::vector<double> coeffs) {
    return CameraModel::Create({size, size, 50, 50, size / 2.0, size / 2.0,
                                DistortionModel::kRadtan, std::move(coeffs)})
        .status()
        .message();
  };
  // The 100×100 image reaches radius 1.41, past the peak of r (1 − 0.5 r²).
  EXPECT_NE(refused(100, {-0.5, 0, 0, 0}).find("cannot be inverted at pixel"), std::string::npos);
  EXPECT_NE(refused(100, {100, 100, 0, 0}).find("fold towards the centre"), std::string::npos)
      << refused(100, {100, 100, 0, 0});
  EXPECT_EQ(refused(100, {-0.3, 0.1, 0.001, 0.001}), "");  // a DAVIS lens
}

TEST(CameraModel, CreateRejectsBadIntrinsics) {
  auto with = [](auto change) {
    CameraIntrinsics in = testing::DsecLeft().raw;
    change(in);
    return CameraModel::Create(in).status();
  };
  EXPECT_NE(with([](CameraIntrinsics& in) { in.fx = -1; }).message().find("focal lengths"),
            std::string::npos);
  EXPECT_NE(with([](CameraIntrinsics& in) { in.width = 0; }).message().find("not a sensor size"),
            std::string::npos);
  EXPECT_NE(with([](CameraIntrinsics& in) { in.cx = 5000; }).message().find("principal point"),
            std::string::npos);
  EXPECT_NE(with([](CameraIntrinsics& in) {
              in.coeffs = {0.1, 0.2, 0.3};
            })
                .message()
                .find("4 or 5 coefficients"),
            std::string::npos);
  EXPECT_NE(with([](CameraIntrinsics& in) {
              in.model = DistortionModel::kEquidistant;
              in.coeffs = {0.1, 0.2, 0.3, 0.4, 0.5};
            })
                .message()
                .find("equidistant takes 4"),
            std::string::npos);
  EXPECT_TRUE(with([](CameraIntrinsics&) {}).ok());
}

}  // namespace
}  // namespace aavio::geometry
