#pragma once
/// SE(3) as rotation + translation. Naming: T_a_b maps points from frame b into frame a,
/// p_a = T_a_b * p_b, and composes as T_a_c = T_a_b * T_b_c (docs/conventions.md).

#include <Eigen/Core>

#include "aavio/geometry/rotation.hpp"

namespace aavio::geometry {

struct RigidTransform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  RigidTransform() = default;
  RigidTransform(Eigen::Matrix3d rotation, Eigen::Vector3d translation)
      : R(std::move(rotation)), t(std::move(translation)) {}

  static RigidTransform Identity() { return {}; }
  /// From a 3x4 [R | t] or 4x4 matrix (R is used as given; orthonormalise before if needed).
  static RigidTransform FromMatrix(const Eigen::Matrix<double, 3, 4>& Rt);
  static RigidTransform FromMatrix(const Eigen::Matrix4d& T);
  Eigen::Matrix4d Matrix() const;

  RigidTransform Inverse() const { return {R.transpose(), -(R.transpose() * t)}; }
  RigidTransform operator*(const RigidTransform& other) const {
    return {R * other.R, R * other.t + t};
  }
  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return R * p + t; }

  Eigen::Quaterniond Quaternion() const { return RotationToQuaternion(R); }
};

/// exp of a twist (ρ, φ) = (translation part, rotation part), as in Sophus/Barfoot:
/// R = Exp(φ), t = V(φ) ρ.
RigidTransform ExpSE3(const Eigen::Matrix<double, 6, 1>& twist);
/// Inverse of ExpSE3.
Eigen::Matrix<double, 6, 1> LogSE3(const RigidTransform& T);

/// Pose interpolation used for stamped poses: rotation by slerp, translation linearly
/// (alpha = 0 gives a, 1 gives b; values outside [0, 1] extrapolate).
RigidTransform InterpolatePose(const RigidTransform& a, const RigidTransform& b, double alpha);

}  // namespace aavio::geometry
