#include "aavio/geometry/stereo_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/fixtures/cameras.hpp"

namespace aavio::geometry {
namespace {

// The rpg DAVIS240C pair (ESVO calibration).
StereoRigParams RpgParams() {
  const testing::RealCamera left = testing::RpgLeft();
  const testing::RealCamera right = testing::RpgRight();
  StereoRigParams p{left.Model(), right.Model(), left.R_rect, right.R_rect,
                    left.P,       right.P,       {},          std::nullopt};
  Eigen::Matrix<double, 3, 4> T;
  T << 0.9991089760393723, -0.04098010198963204, 0.010093821797214667, -0.1479883582369969,
      0.04098846609277917, 0.9991594254283246, -0.000623077121092687, -0.003289908601915284,
      -0.010059803423311134, 0.0010362522169301642, 0.9999488619606629, 0.0026798262366239016;
  p.T_right_left = RigidTransform::FromMatrix(T);
  return p;
}

TEST(StereoRig, DerivesBaselineAndRectifiedGeometry) {
  std::vector<std::string> warnings;
  Expected<StereoRig> rig = StereoRig::Create(RpgParams(), &warnings);
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  EXPECT_NEAR(rig->baseline_m(), 23.2327 / 156.925, 1e-12);  // rpg calibration: 0.1481 m
  EXPECT_DOUBLE_EQ(rig->focal_px(), 156.925);
  EXPECT_NEAR(rig->DisparityAtDepth(1.0), 23.2327, 1e-9);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  // Rectified right ← rectified left is the pure baseline translation.
  const RigidTransform T = rig->T_rect_right_rect_left();
  EXPECT_EQ(T.t, Eigen::Vector3d(-rig->baseline_m(), 0, 0));
}

TEST(StereoRig, WithBaselineMovesOnlyTheRightCameraAlongTheBaseline) {
  Expected<StereoRig> rig = StereoRig::Create(RpgParams());
  ASSERT_TRUE(rig.ok());
  Expected<StereoRig> wide = rig->WithBaseline(0.6);
  ASSERT_TRUE(wide.ok()) << wide.status().message();
  EXPECT_NEAR(wide->baseline_m(), 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(wide->focal_px(), rig->focal_px());
  EXPECT_DOUBLE_EQ(wide->cx_right(), rig->cx_right());
  EXPECT_NEAR(wide->DisparityAtDepth(2.0), 156.925 * 0.6 / 2.0 + rig->cx_left() - rig->cx_right(),
              1e-9);
  EXPECT_TRUE(wide->T_right_left().R.isApprox(rig->T_right_left().R, 1e-12));
  EXPECT_NEAR(wide->T_right_left().t.normalized().dot(rig->T_right_left().t.normalized()), 1.0,
              1e-12);
  EXPECT_FALSE(rig->WithBaseline(0.0).ok());
  EXPECT_FALSE(rig->WithBaseline(-0.1).ok());
  EXPECT_FALSE(rig->WithBaseline(std::nan("")).ok());
}

TEST(StereoRig, ImuExtrinsicIsComposedWithTheRectification) {
  StereoRigParams p = RpgParams();
  p.T_imu_left =
      RigidTransform(ExpSO3(Eigen::Vector3d(0.01, -0.02, 0.03)), Eigen::Vector3d(0.1, 0, 0));
  const StereoRig rig = *StereoRig::Create(p);
  EXPECT_FALSE(StereoRig::Create(RpgParams())->T_imu_rect_left().has_value());
  // p_imu = T_imu_left · R_rectᵀ · p_rect for a point given in the rectified left frame.
  const Eigen::Vector3d p_rect(0.3, -0.1, 2.0);
  const Eigen::Vector3d expected =
      *rig.T_imu_left() * (rig.R_rect_left_left().transpose() * p_rect);
  EXPECT_LT((*rig.T_imu_rect_left() * p_rect - expected).norm(), 1e-14);
}

TEST(StereoRig, WarnsWhenTheExtrinsicDisagreesWithTheRectification) {
  StereoRigParams p = RpgParams();
  p.T_right_left.t *= 1.2;  // a 20 % longer baseline than P_right says
  std::vector<std::string> warnings;
  ASSERT_TRUE(StereoRig::Create(p, &warnings).ok());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("T_right_left disagrees with the rectification"), std::string::npos);
}

TEST(StereoRig, RejectsInconsistentRigs) {
  auto error = [](auto change) {
    StereoRigParams p = RpgParams();
    change(p);
    Expected<StereoRig> rig = StereoRig::Create(p);
    EXPECT_FALSE(rig.ok());
    return rig.status().message();
  };
  EXPECT_NE(
      error([](StereoRigParams& p) { p.P_right(0, 3) = 23.2327; }).find("swap the left and right"),
      std::string::npos);
  // A baseline in the wrong unit: 1e-12 m, or P(0,3) in millimetres (148 m).
  EXPECT_NE(error([](StereoRigParams& p) { p.P_right(0, 3) = -1e-10; }).find("outside the 5 mm"),
            std::string::npos);
  EXPECT_NE(
      error([](StereoRigParams& p) { p.P_right(0, 3) *= 1000.0; }).find("pixels times metres"),
      std::string::npos);
  EXPECT_NE(error([](StereoRigParams& p) { p.P_right(1, 3) = -5.0; }).find("vertical stereo rig"),
            std::string::npos);
  EXPECT_NE(error([](StereoRigParams& p) { p.P_right(0, 0) = 150.0; }).find("not rectified"),
            std::string::npos);
  EXPECT_NE(error([](StereoRigParams& p) {
              p.R_rect_left_left(0, 0) = 0.9;
            }).find("left rectification rotation is not a rotation"),
            std::string::npos);
  EXPECT_NE(error([](StereoRigParams& p) { p.P_left(0, 3) = 1.0; }).find("zero last column"),
            std::string::npos);
  EXPECT_NE(
      error([](StereoRigParams& p) { p.P_left(2, 2) = 2.0; }).find("not a rectified projection"),
      std::string::npos);
  EXPECT_NE(error([](StereoRigParams& p) {
              CameraIntrinsics in = p.right.intrinsics();
              in.width = 320;
              p.right = *CameraModel::Create(in);
            }).find("image sizes differ"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::geometry
