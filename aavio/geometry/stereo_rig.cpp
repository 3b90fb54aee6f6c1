#include "aavio/geometry/stereo_rig.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>

#include "aavio/common/format.hpp"

namespace aavio::geometry {

namespace {

Status CheckProjection(const ProjectionMatrix& P, const std::string& name) {
  if (!P.allFinite()) return InvalidArgument(name + " has non-finite entries");
  if (!(P(0, 0) > 0.0) || !(P(1, 1) > 0.0)) {
    return InvalidArgument(name + ": focal lengths P(0,0), P(1,1) must be positive");
  }
  if (P(0, 1) != 0.0 || P(1, 0) != 0.0 || P(2, 0) != 0.0 || P(2, 1) != 0.0 || P(2, 2) != 1.0 ||
      P(2, 3) != 0.0) {
    return InvalidArgument(name + " is not a rectified projection [f 0 cx tx; 0 f cy 0; 0 0 1 0]");
  }
  return Status::Ok();
}

}  // namespace

Expected<StereoRig> StereoRig::Create(StereoRigParams p, std::vector<std::string>* warnings) {
  auto warn = [&](std::string message) {
    if (warnings) warnings->push_back(std::move(message));
  };
  if (p.left.width() != p.right.width() || p.left.height() != p.right.height()) {
    return InvalidArgument("left and right image sizes differ (" + std::to_string(p.left.width()) +
                           "x" + std::to_string(p.left.height()) + " vs " +
                           std::to_string(p.right.width()) + "x" +
                           std::to_string(p.right.height()) + "); aavio needs equal sizes");
  }
  AAVIO_RETURN_IF_ERROR(ValidateRotation(p.R_rect_left_left, "left rectification rotation"));
  AAVIO_RETURN_IF_ERROR(ValidateRotation(p.R_rect_right_right, "right rectification rotation"));
  AAVIO_RETURN_IF_ERROR(ValidateRotation(p.T_right_left.R, "T_right_left rotation"));
  if (p.T_imu_left) AAVIO_RETURN_IF_ERROR(ValidateRotation(p.T_imu_left->R, "IMU-camera rotation"));
  AAVIO_RETURN_IF_ERROR(CheckProjection(p.P_left, "left projection matrix"));
  AAVIO_RETURN_IF_ERROR(CheckProjection(p.P_right, "right projection matrix"));
  if (p.P_left(0, 3) != 0.0 || p.P_left(1, 3) != 0.0) {
    return InvalidArgument("left projection matrix must have a zero last column (got P(0,3) = " +
                           StrFormat("%g", p.P_left(0, 3)) + ")");
  }
  if (p.P_right(1, 3) != 0.0) {
    return InvalidArgument(
        "right projection matrix has P(1,3) != 0: a vertical stereo rig, which aavio does not "
        "support (rectify to a horizontal baseline)");
  }
  if (!(p.P_right(0, 3) < 0.0)) {
    return InvalidArgument(
        "right projection matrix has P(0,3) = " + StrFormat("%g", p.P_right(0, 3)) +
        " but must be −f·baseline < 0: the right camera would be left of the left one; "
        "swap the left and right files or fix the sign");
  }
  const double f = p.P_left(0, 0);
  const double tolerance_px = 1e-4 * f;  // files print ~7 significant digits
  if (std::abs(p.P_right(0, 0) - f) > tolerance_px ||
      std::abs(p.P_right(1, 1) - p.P_left(1, 1)) > tolerance_px ||
      std::abs(p.P_right(1, 2) - p.P_left(1, 2)) > tolerance_px) {
    return InvalidArgument(
        "left and right projection matrices disagree on f or cy: the pair is not rectified "
        "(left f = " +
        StrFormat("%g, cy = %g", f, p.P_left(1, 2)) +
        "; right f = " + StrFormat("%g, cy = %g", p.P_right(0, 0), p.P_right(1, 2)) + ")");
  }
  if (std::abs(p.P_left(0, 0) - p.P_left(1, 1)) > tolerance_px) {
    return InvalidArgument("rectified projection has fx != fy (" +
                           StrFormat("%g vs %g", p.P_left(0, 0), p.P_left(1, 1)) +
                           "); aavio expects square rectified pixels");
  }

  const Eigen::Vector3d centre = p.P_right.leftCols<3>().inverse() * p.P_right.col(3);
  const double baseline_m = centre.norm();
  // 5 mm to 5 m covers every stereo event rig (DAVIS pairs 0.1 m, cars 0.6 m); outside it a unit is
  // wrong, most often P(0,3) written in millimetres or without the focal length.
  if (!(baseline_m >= 0.005 && baseline_m <= 5.0)) {
    return InvalidArgument(
        "right projection matrix gives a baseline of " + StrFormat("%g m", baseline_m) +
        " (P(0,3) = " + StrFormat("%g", p.P_right(0, 3)) +
        " = −f·baseline), outside the 5 mm – 5 m of a stereo rig; P(0,3) must be in pixels "
        "times metres");
  }

  p.R_rect_left_left = Orthonormalize(p.R_rect_left_left);
  p.R_rect_right_right = Orthonormalize(p.R_rect_right_right);
  p.T_right_left.R = Orthonormalize(p.T_right_left.R);
  if (p.T_imu_left) p.T_imu_left->R = Orthonormalize(p.T_imu_left->R);

  // T_right_left must agree with the rectification: R_rectR · R_RL · R_rectLᵀ = I and
  // R_rectR · t_RL = (−b, 0, 0) (docs/io.md). Calibration tools write these separately, so
  // small disagreements are common; report them, the rectified geometry (R_rect, P) wins.
  const Eigen::Matrix3d R_check =
      p.R_rect_right_right * p.T_right_left.R * p.R_rect_left_left.transpose();
  const double angle_deg = LogSO3(R_check).norm() * 180.0 / M_PI;
  const Eigen::Vector3d t_check = p.R_rect_right_right * p.T_right_left.t;
  const double t_error_m = (t_check - Eigen::Vector3d(-baseline_m, 0.0, 0.0)).norm();
  if (angle_deg > 0.1 || t_error_m > 0.01 * baseline_m) {
    warn("T_right_left disagrees with the rectification by " + StrFormat("%.3f deg", angle_deg) +
         StrFormat(" and %.4f m (%.1f %% of the baseline); the rectified projection is used",
                   t_error_m, 100.0 * t_error_m / baseline_m));
  }
  if (std::abs(p.P_left(0, 2) - p.P_right(0, 2)) > 1e-6) {
    warn("rectified principal points differ (cx left " +
         StrFormat("%.3f, right %.3f): disparities include an offset of %.3f px", p.P_left(0, 2),
                   p.P_right(0, 2), p.P_left(0, 2) - p.P_right(0, 2)));
  }
  return StereoRig(std::move(p), baseline_m);
}

Expected<StereoRig> StereoRig::WithBaseline(double baseline_m) const {
  if (!(baseline_m > 0.0) || !std::isfinite(baseline_m))
    return InvalidArgument("a stereo baseline must be a positive length in metres, not " +
                           std::to_string(baseline_m));
  StereoRigParams p = p_;
  const double scale = baseline_m / baseline_m_;
  p.T_right_left.t *= scale;
  p.P_right.col(3) *= scale;
  return Create(std::move(p));
}

RigidTransform StereoRig::T_rect_right_rect_left() const {
  return {Eigen::Matrix3d::Identity(), Eigen::Vector3d(-baseline_m_, 0.0, 0.0)};
}

std::optional<RigidTransform> StereoRig::T_imu_rect_left() const {
  if (!p_.T_imu_left) return std::nullopt;
  const RigidTransform T_left_rect_left(p_.R_rect_left_left.transpose(), Eigen::Vector3d::Zero());
  return *p_.T_imu_left * T_left_rect_left;
}

double StereoRig::DisparityAtDepth(double depth_m) const {
  return focal_px() * baseline_m_ / depth_m + (cx_left() - cx_right());
}

}  // namespace aavio::geometry
