#pragma once
/// SO(3) helpers over Eigen (Sophus is not packaged for Debian 12). Conventions: rotations are
/// active, R_a_b maps coordinates in frame b to frame a; quaternions are Hamilton, stored by Eigen
/// as (w, x, y, z) and written in files as (qx, qy, qz, qw).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "aavio/common/status.hpp"

namespace aavio::geometry {

/// [w]x: the skew-symmetric matrix with Hat(w) * v = w.cross(v).
Eigen::Matrix3d Hat(const Eigen::Vector3d& w);
/// Inverse of Hat (reads the off-diagonal entries; no symmetry check).
Eigen::Vector3d Vee(const Eigen::Matrix3d& W);

/// Rodrigues' formula: rotation by angle |w| about w/|w|. Accurate near 0 (Taylor terms).
Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& w);
/// Rotation vector of R, angle in [0, π]. Accurate near 0 and near π.
Eigen::Vector3d LogSO3(const Eigen::Matrix3d& R);
/// The left Jacobian of SO(3): Exp(w + δ) ≈ Exp(Jl(w) δ)·Exp(w); also the V of SE(3)'s
/// exponential, t = Jl(φ)·ρ.
Eigen::Matrix3d LeftJacobianSO3(const Eigen::Vector3d& w);
/// The right Jacobian of SO(3): Exp(w + δ) ≈ Exp(w)·Exp(Jr(w) δ) (Forster et al. 2017, eq. 8).
Eigen::Matrix3d RightJacobianSO3(const Eigen::Vector3d& w);
/// Its inverse: Log(Exp(w)·Exp(δ)) ≈ w + Jr⁻¹(w) δ. For |w| < π.
Eigen::Matrix3d InverseRightJacobianSO3(const Eigen::Vector3d& w);

/// Cayley map (docs/tracking.md): R(c) = ((1 − cᵀc) I + 2 c cᵀ + 2 [c]x) / (1 + cᵀc).
/// c = tan(θ/2)·axis, so R(c) ≈ I + 2[c]x near 0; singular at θ = π.
Eigen::Matrix3d CayleyToRotation(const Eigen::Vector3d& c);
/// Inverse Cayley map: c = q_vec / q_w. Undefined for θ = π (q_w = 0).
Eigen::Vector3d RotationToCayley(const Eigen::Matrix3d& R);

Eigen::Matrix3d QuaternionToRotation(const Eigen::Quaterniond& q);  ///< normalises q first
Eigen::Quaterniond RotationToQuaternion(const Eigen::Matrix3d& R);  ///< q_w >= 0

/// The rotation closest to M in the Frobenius norm (SVD, det fixed to +1).
Eigen::Matrix3d Orthonormalize(const Eigen::Matrix3d& M);

/// ‖R Rᵀ − I‖_max and det(R): how far a matrix read from a file is from a rotation.
struct RotationError {
  double orthogonality = 0.0;  ///< max |(R Rᵀ − I)_ij|
  double determinant = 0.0;
};
RotationError MeasureRotationError(const Eigen::Matrix3d& R);

/// Ok if R is a rotation to within `tolerance` (max |R Rᵀ − I|; 1e-3 accepts the 6 digits that
/// calibration files print) with det > 0; otherwise InvalidArgument naming `name`.
Status ValidateRotation(const Eigen::Matrix3d& R, const std::string& name, double tolerance = 1e-3);

/// Angle of the rotation R_a * R_b⁻¹ [rad]: the distance between two rotations.
double RotationDistance(const Eigen::Matrix3d& R_a, const Eigen::Matrix3d& R_b);

}  // namespace aavio::geometry
