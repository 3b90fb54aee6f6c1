#include "aavio/geometry/calibration_difference.hpp"

#include <gtest/gtest.h>

#include <functional>

#include "tests/fixtures/cameras.hpp"

namespace aavio::geometry {
namespace {

// The rpg DAVIS240C pair, its raw cameras changed by `change` (the rectification kept).
StereoRig RpgRig(
    const std::function<void(CameraIntrinsics* left, CameraIntrinsics* right)>& change = nullptr) {
  testing::RealCamera left = testing::RpgLeft(), right = testing::RpgRight();
  if (change) change(&left.raw, &right.raw);
  // The extrinsic that rectification implies: R_rect_rightᵀ R_rect_left, R_rect_rightᵀ (−b, 0, 0).
  const double baseline_m = -right.P(0, 3) / right.P(0, 0);
  const RigidTransform T_right_left(right.R_rect.transpose() * left.R_rect,
                                    right.R_rect.transpose() * Eigen::Vector3d(-baseline_m, 0, 0));
  return *StereoRig::Create({left.Model(), right.Model(), left.R_rect, right.R_rect, left.P,
                             right.P, T_right_left, std::nullopt});
}

TEST(CalibrationDifference, NoneBetweenACalibrationAndItself) {
  const StereoRig rig = RpgRig();
  Expected<CalibrationDifference> d = CompareCalibrations(rig, rig);
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_GE(d->directions, 50);  // a few corners of one camera the other does not see
  EXPECT_NEAR(d->disparity_offset_px, 0.0, 1e-6);
  EXPECT_NEAR(d->disparity_offset_min_px, 0.0, 1e-6);
  EXPECT_NEAR(d->disparity_offset_max_px, 0.0, 1e-6);
  EXPECT_NEAR(d->max_row_offset_px, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(d->fb_ratio, 1.0);
}

TEST(CalibrationDifference, APrincipalPointErrorIsAnOffsetOverTheWholeView) {
  // The right camera believed 0.5 px to the right of where it is: every rectified right pixel
  // lies about 0.5·f/fx further left than the truth puts it, so disparities grow by that much
  // (the cameras without lens distortion, which would stretch the shift towards the edges).
  auto pinhole = [](CameraIntrinsics* left, CameraIntrinsics* right) {
    left->model = right->model = DistortionModel::kNone;
    left->coeffs.clear();
    right->coeffs.clear();
  };
  const StereoRig truth = RpgRig(pinhole);
  const StereoRig used = RpgRig([&](CameraIntrinsics* left, CameraIntrinsics* right) {
    pinhole(left, right);
    right->cx += 0.5;
    right->cy += 0.3;
  });
  Expected<CalibrationDifference> d = CompareCalibrations(used, truth);
  ASSERT_TRUE(d.ok()) << d.status().message();
  const double expected = 0.5 * truth.focal_px() / testing::RpgRight().raw.fx;
  EXPECT_NEAR(d->disparity_offset_px, expected, 0.03);
  EXPECT_NEAR(d->disparity_offset_min_px, expected, 0.05);
  EXPECT_NEAR(d->disparity_offset_max_px, expected, 0.05);
  // Its row moves the other way: the left row minus the right one grows.
  EXPECT_NEAR(d->row_offset_px, 0.3 * truth.focal_px() / testing::RpgRight().raw.fy, 0.03);
  EXPECT_DOUBLE_EQ(d->fb_ratio, 1.0);
}

TEST(CalibrationDifference, AFocalLengthErrorVariesOverTheView) {
  // A right focal length 1 % long: the rectified right image shrinks about its centre, so the
  // offset changes sign across the view (±1 % of the half width at the edges).
  const StereoRig truth = RpgRig();
  const StereoRig used = RpgRig([](CameraIntrinsics*, CameraIntrinsics* right) {
    right->fx *= 1.01;
    right->fy *= 1.01;
  });
  Expected<CalibrationDifference> d = CompareCalibrations(used, truth);
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_LT(d->disparity_offset_min_px, -0.5);
  EXPECT_GT(d->disparity_offset_max_px, 0.5);
  EXPECT_LT(std::abs(d->disparity_offset_px), 0.5);
}

TEST(CalibrationDifference, ABaselineErrorIsAScaleNotAnOffset) {
  const StereoRig truth = RpgRig();
  Expected<StereoRig> used = truth.WithBaseline(truth.baseline_m() * 1.02);
  ASSERT_TRUE(used.ok());
  Expected<CalibrationDifference> d = CompareCalibrations(*used, truth);
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_NEAR(d->fb_ratio, 1.02, 1e-12);
  EXPECT_NEAR(d->disparity_offset_px, 0.0, 1e-6);
}

TEST(CalibrationDifference, RigsOfDifferentSensorsAreAnError) {
  const StereoRig truth = RpgRig();
  const StereoRig other = RpgRig(
      [](CameraIntrinsics* left, CameraIntrinsics* right) { left->width = right->width = 346; });
  Expected<CalibrationDifference> d = CompareCalibrations(other, truth);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.status().message().find("different sensors"), std::string::npos);
}

}  // namespace
}  // namespace aavio::geometry
