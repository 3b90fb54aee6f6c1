#include "aavio/eval/alignment.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace aavio::eval {

const char* AlignmentName(Alignment alignment) {
  switch (alignment) {
    case Alignment::kNone: return "none";
    case Alignment::kSe3: return "se3";
    case Alignment::kSim3: return "sim3";
    case Alignment::kPosYaw: return "posyaw";
  }
  return "?";
}

Expected<Alignment> ParseAlignment(const std::string& name) {
  for (Alignment a : {Alignment::kNone, Alignment::kSe3, Alignment::kSim3, Alignment::kPosYaw})
    if (name == AlignmentName(a)) return a;
  return InvalidArgument("unknown alignment '" + name +
                         "'; use se3 (stereo), sim3 (monocular), posyaw (visual-inertial) or none");
}

Similarity Align(const std::vector<PosePair>& pairs, Alignment alignment, int num_frames) {
  Similarity S;
  const std::size_t n_used =
      num_frames <= 0 ? pairs.size() : std::min(pairs.size(), static_cast<std::size_t>(num_frames));
  const std::size_t min_pairs = alignment == Alignment::kPosYaw ? 2 : 3;
  if (alignment == Alignment::kNone || n_used < min_pairs) return S;
  const double n = static_cast<double>(n_used);
  Eigen::Vector3d mu_e = Eigen::Vector3d::Zero(), mu_g = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n_used; ++i) {
    mu_e += pairs[i].T_world_est.t;
    mu_g += pairs[i].T_world_gt.t;
  }
  mu_e /= n;
  mu_g /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();  // Σ (g − μg)(e − μe)ᵀ / n
  double var_e = 0.0;
  for (std::size_t i = 0; i < n_used; ++i) {
    cov += (pairs[i].T_world_gt.t - mu_g) * (pairs[i].T_world_est.t - mu_e).transpose();
    var_e += (pairs[i].T_world_est.t - mu_e).squaredNorm();
  }
  cov /= n;
  var_e /= n;
  if (alignment == Alignment::kPosYaw) {
    // maximise trace(Rz(θ) C) with C = covᵀ = Σ (e − μe)(g − μg)ᵀ / n
    const Eigen::Matrix3d C = cov.transpose();
    const double theta = std::atan2(C(0, 1) - C(1, 0), C(0, 0) + C(1, 1));
    S.R = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  } else {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
    S.R = svd.matrixU() * D * svd.matrixV().transpose();
    if (alignment == Alignment::kSim3 && var_e > 0.0)
      S.scale = (svd.singularValues().asDiagonal() * D).trace() / var_e;
  }
  S.t = mu_g - S.scale * (S.R * mu_e);
  return S;
}

}  // namespace aavio::eval
