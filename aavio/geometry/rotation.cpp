#include "aavio/geometry/rotation.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "aavio/common/format.hpp"

namespace aavio::geometry {

Eigen::Matrix3d Hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0.0, -w.z(), w.y(),  //
      w.z(), 0.0, -w.x(),   //
      -w.y(), w.x(), 0.0;
  return W;
}

Eigen::Vector3d Vee(const Eigen::Matrix3d& W) {
  return {W(2, 1), W(0, 2), W(1, 0)};
}

Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& w) {
  const double theta2 = w.squaredNorm();
  const Eigen::Matrix3d W = Hat(w);
  double a;  // sin θ / θ
  double b;  // (1 − cos θ) / θ²
  if (theta2 < 1e-10) {
    a = 1.0 - theta2 / 6.0;
    b = 0.5 - theta2 / 24.0;
  } else {
    const double theta = std::sqrt(theta2);
    a = std::sin(theta) / theta;
    b = (1.0 - std::cos(theta)) / theta2;
  }
  return Eigen::Matrix3d::Identity() + a * W + b * W * W;
}

namespace {

// The two coefficients of SO(3)'s Jacobians: b = (1 − cos θ)/θ², c = (θ − sin θ)/θ³, by their
// series below θ = 1e-4 (where the closed forms lose digits to cancellation).
void JacobianCoefficients(double theta2, double* b, double* c) {
  if (theta2 < 1e-8) {
    *b = 0.5 - theta2 / 24.0;
    *c = 1.0 / 6.0 - theta2 / 120.0;
    return;
  }
  const double theta = std::sqrt(theta2);
  *b = (1.0 - std::cos(theta)) / theta2;
  *c = (theta - std::sin(theta)) / (theta2 * theta);
}

}  // namespace

Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& w) {
  const Eigen::Matrix3d W = Hat(w);
  double b = 0.0, c = 0.0;
  JacobianCoefficients(w.squaredNorm(), &b, &c);
  return Eigen::Matrix3d::Identity() + b * W + c * W * W;
}

Eigen::Matrix3d RightJacobianSO3(const Eigen::Vector3d& w) {
  const Eigen::Matrix3d W = Hat(w);
  double b = 0.0, c = 0.0;
  JacobianCoefficients(w.squaredNorm(), &b, &c);
  return Eigen::Matrix3d::Identity() - b * W + c * W * W;
}

Eigen::Matrix3d InverseRightJacobianSO3(const Eigen::Vector3d& w) {
  const double theta2 = w.squaredNorm();
  const Eigen::Matrix3d W = Hat(w);
  double d;  // 1/θ² − (1 + cos θ) / (2 θ sin θ)
  if (theta2 < 1e-8) {
    d = 1.0 / 12.0 + theta2 / 720.0;
  } else {
    const double theta = std::sqrt(theta2);
    d = 1.0 / theta2 - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  }
  return Eigen::Matrix3d::Identity() + 0.5 * W + d * W * W;
}

Eigen::Vector3d LogSO3(const Eigen::Matrix3d& R) {
  // Through the quaternion: numerically well behaved over the whole range, including θ ≈ π.
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-10) return 2.0 * v / q.w();  // θ ≈ 2 s / w
  const double theta = 2.0 * std::atan2(s, q.w());
  return theta / s * v;
}

Eigen::Matrix3d CayleyToRotation(const Eigen::Vector3d& c) {
  const double ctc = c.squaredNorm();
  return ((1.0 - ctc) * Eigen::Matrix3d::Identity() + 2.0 * c * c.transpose() + 2.0 * Hat(c)) /
         (1.0 + ctc);
}

Eigen::Vector3d RotationToCayley(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q = RotationToQuaternion(R);
  return q.vec() / q.w();
}

Eigen::Matrix3d QuaternionToRotation(const Eigen::Quaterniond& q) {
  return q.normalized().toRotationMatrix();
}

Eigen::Quaterniond RotationToQuaternion(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(Orthonormalize(R));
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  return q;
}

Eigen::Matrix3d Orthonormalize(const Eigen::Matrix3d& M) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

RotationError MeasureRotationError(const Eigen::Matrix3d& R) {
  RotationError error;
  error.orthogonality = (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  error.determinant = R.determinant();
  return error;
}

Status ValidateRotation(const Eigen::Matrix3d& R, const std::string& name, double tolerance) {
  if (!R.allFinite()) return InvalidArgument(name + " has non-finite entries");
  const RotationError error = MeasureRotationError(R);
  if (error.determinant < 0.0) {
    return InvalidArgument(name + " is a reflection (det = " +
                           StrFormat("%.6f", error.determinant) + "), not a rotation");
  }
  if (error.orthogonality > tolerance) {
    return InvalidArgument(
        name + " is not a rotation: max |R R^T - I| = " + StrFormat("%.3g", error.orthogonality) +
        " (tolerance " + StrFormat("%.0e", tolerance) + ")");
  }
  return Status::Ok();
}

double RotationDistance(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b) {
  return LogSO3(R_a * R_b.transpose()).norm();
}

}  // namespace aavio::geometry
