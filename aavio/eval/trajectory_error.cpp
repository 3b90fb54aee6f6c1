#include "aavio/eval/trajectory_error.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::eval {
namespace {

double Rms(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v)
    s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

double RotationDeg(const Eigen::Matrix3d& R) { return geometry::LogSO3(R).norm() * 180.0 / M_PI; }

}  // namespace

Expected<std::vector<PosePair>> Associate(const std::vector<geometry::StampedPose>& estimate,
                                          const std::vector<geometry::StampedPose>& ground_truth,
                                          TimeNs max_dt_ns) {
  std::vector<PosePair> pairs;
  std::size_t j = 0;
  for (const geometry::StampedPose& e : estimate) {
    while (j + 1 < ground_truth.size() &&
           std::llabs(ground_truth[j + 1].t_ns - e.t_ns) <= std::llabs(ground_truth[j].t_ns - e.t_ns))
      ++j;
    if (ground_truth.empty() || std::llabs(ground_truth[j].t_ns - e.t_ns) > max_dt_ns) continue;
    pairs.push_back({e.t_ns, e.T_world_body, ground_truth[j].T_world_body});
  }
  if (pairs.empty()) {
    return InvalidArgument(
        "no estimated pose has a ground-truth pose within " +
        std::to_string(static_cast<double>(max_dt_ns) * 1e-6) +
        " ms (do the trajectories overlap in time, and use the same clock?)");
  }
  return pairs;
}

Similarity Align(const std::vector<PosePair>& pairs, Alignment alignment) {
  Similarity S;
  if (alignment == Alignment::kNone || pairs.size() < 3) return S;
  const double n = static_cast<double>(pairs.size());
  Eigen::Vector3d mu_e = Eigen::Vector3d::Zero(), mu_g = Eigen::Vector3d::Zero();
  for (const PosePair& p : pairs) {
    mu_e += p.T_world_est.t;
    mu_g += p.T_world_gt.t;
  }
  mu_e /= n;
  mu_g /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double var_e = 0.0;
  for (const PosePair& p : pairs) {
    cov += (p.T_world_gt.t - mu_g) * (p.T_world_est.t - mu_e).transpose();
    var_e += (p.T_world_est.t - mu_e).squaredNorm();
  }
  cov /= n;
  var_e /= n;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  S.R = svd.matrixU() * D * svd.matrixV().transpose();
  if (alignment == Alignment::kSim3 && var_e > 0.0)
    S.scale = (svd.singularValues().asDiagonal() * D).trace() / var_e;
  S.t = mu_g - S.scale * (S.R * mu_e);
  return S;
}

TrajectoryError EvaluateTrajectory(const std::vector<PosePair>& pairs, Alignment alignment,
                                   double rpe_step_s) {
  TrajectoryError e;
  e.pairs = pairs.size();
  e.alignment = Align(pairs, alignment);
  e.rpe_step_s = rpe_step_s;
  std::vector<double> ate, ate_rot;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PosePair& p = pairs[i];
    ate.push_back((e.alignment.Apply(p.T_world_est.t) - p.T_world_gt.t).norm());
    ate_rot.push_back(RotationDeg(p.T_world_gt.R.transpose() * e.alignment.R * p.T_world_est.R));
    if (i > 0) e.path_length_m += (p.T_world_gt.t - pairs[i - 1].T_world_gt.t).norm();
  }
  if (!ate.empty()) {
    e.ate_rmse_m = Rms(ate);
    e.ate_rotation_rmse_deg = Rms(ate_rot);
    double sum = 0.0;
    for (const double x : ate)
      sum += x;
    e.ate_mean_m = sum / static_cast<double>(ate.size());
    e.ate_max_m = *std::max_element(ate.begin(), ate.end());
    std::vector<double> sorted = ate;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                     sorted.end());
    e.ate_median_m = sorted[sorted.size() / 2];
  }
  // RPE: relative motion over the step, estimate vs ground truth (translation scaled by the
  // alignment's scale so that sim3 results are in metres).
  std::vector<double> rpe_t, rpe_r;
  const TimeNs step = SecondsToNs(rpe_step_s);
  std::size_t j = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < pairs.size() && pairs[j].t_ns - pairs[i].t_ns < step)
      ++j;
    if (j >= pairs.size()) break;
    const geometry::RigidTransform de = pairs[i].T_world_est.Inverse() * pairs[j].T_world_est;
    const geometry::RigidTransform dg = pairs[i].T_world_gt.Inverse() * pairs[j].T_world_gt;
    rpe_t.push_back((e.alignment.scale * de.t - dg.t).norm());
    rpe_r.push_back(RotationDeg(dg.R.transpose() * de.R));
  }
  e.rpe_translation_rmse_m = Rms(rpe_t);
  e.rpe_rotation_rmse_deg = Rms(rpe_r);
  return e;
}

}  // namespace aavio::eval
