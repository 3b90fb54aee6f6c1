#include "aavio/geometry/rigid_transform.hpp"

#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::geometry {

RigidTransform RigidTransform::FromMatrix(const Eigen::Matrix<double, 3, 4>& Rt) {
  return {Rt.leftCols<3>(), Rt.col(3)};
}

RigidTransform RigidTransform::FromMatrix(const Eigen::Matrix4d& T) {
  return {T.topLeftCorner<3, 3>(), T.topRightCorner<3, 1>()};
}

Eigen::Matrix4d RigidTransform::Matrix() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = t;
  return T;
}

RigidTransform ExpSE3(const Eigen::Matrix<double, 6, 1>& twist) {
  const Eigen::Vector3d rho = twist.head<3>();
  const Eigen::Vector3d phi = twist.tail<3>();
  return {ExpSO3(phi), LeftJacobianSO3(phi) * rho};
}

Eigen::Matrix<double, 6, 1> LogSE3(const RigidTransform& T) {
  const Eigen::Vector3d phi = LogSO3(T.R);
  Eigen::Matrix<double, 6, 1> twist;
  twist.head<3>() = LeftJacobianSO3(phi).inverse() * T.t;
  twist.tail<3>() = phi;
  return twist;
}

RigidTransform InterpolatePose(const RigidTransform& a, const RigidTransform& b, double alpha) {
  const Eigen::Quaterniond qa = a.Quaternion();
  Eigen::Quaterniond qb = b.Quaternion();
  Eigen::Matrix3d R;
  if (alpha >= 0.0 && alpha <= 1.0) {
    R = qa.slerp(alpha, qb).toRotationMatrix();
  } else {
    // Extrapolation: R_a · Exp(α · Log(R_aᵀ R_b)).
    R = a.R * ExpSO3(alpha * LogSO3(a.R.transpose() * b.R));
  }
  return {Orthonormalize(R), (1.0 - alpha) * a.t + alpha * b.t};
}

}  // namespace aavio::geometry
