#include "aavio/eval/trajectory_error.hpp"

#include <Eigen/Eigenvalues>
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

double RotationDeg(const Eigen::Matrix3d& R) {
  return geometry::LogSO3(R).norm() * 180.0 / M_PI;
}

// A rotation about axis a moves the positions only by their spread perpendicular to a, so
// position errors of rmse r leave it uncertain by about r / that spread; the worst axis is the
// main direction of the path (perpendicular spread sqrt(λ2 + λ3)); a yaw-only alignment is
// pinned by the horizontal spread alone.
double AlignmentRotationSigmaDeg(const std::vector<PosePair>& pairs, std::size_t used,
                                 Alignment alignment, double rmse_m) {
  if (alignment == Alignment::kNone || used == 0) return 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < used; ++i)
    mean += pairs[i].T_world_gt.t;
  mean /= static_cast<double>(used);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < used; ++i) {
    const Eigen::Vector3d d = pairs[i].T_world_gt.t - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(used);
  double spread2 = 0.0;
  if (alignment == Alignment::kPosYaw) {
    spread2 = cov(0, 0) + cov(1, 1);
  } else {
    const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues();
    spread2 = l(0) + l(1);  // ascending: the two smallest
  }
  if (rmse_m <= 0.0) return 0.0;
  const double sigma = spread2 > 0.0 ? rmse_m / std::sqrt(spread2) : M_PI;
  return std::min(sigma, M_PI) * 180.0 / M_PI;
}

// The chordal mean of R_gt·R_estᵀ (projected onto SO(3)), then the rms angle left.
double OrientationAlignedRotationRmsDeg(const std::vector<PosePair>& pairs) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const PosePair& p : pairs)
    sum += p.T_world_gt.R * p.T_world_est.R.transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  const Eigen::Matrix3d R = svd.matrixU() * D * svd.matrixV().transpose();
  std::vector<double> angles;
  angles.reserve(pairs.size());
  for (const PosePair& p : pairs)
    angles.push_back(RotationDeg(p.T_world_gt.R.transpose() * R * p.T_world_est.R));
  return Rms(angles);
}

}  // namespace

Expected<std::vector<PosePair>> Associate(const std::vector<geometry::StampedPose>& estimate,
                                          const std::vector<geometry::StampedPose>& ground_truth,
                                          TimeNs max_dt_ns) {
  struct Candidate {
    TimeNs dt;
    std::size_t e, g;
  };
  std::vector<Candidate> candidates;
  std::size_t first = 0;
  for (std::size_t e = 0; e < estimate.size(); ++e) {
    while (first < ground_truth.size() && ground_truth[first].t_ns < estimate[e].t_ns - max_dt_ns)
      ++first;
    for (std::size_t g = first;
         g < ground_truth.size() && ground_truth[g].t_ns <= estimate[e].t_ns + max_dt_ns; ++g)
      candidates.push_back({std::llabs(ground_truth[g].t_ns - estimate[e].t_ns), e, g});
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.dt < b.dt; });
  std::vector<char> used_e(estimate.size(), 0), used_g(ground_truth.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  for (const Candidate& c : candidates) {
    if (used_e[c.e] || used_g[c.g]) continue;
    used_e[c.e] = used_g[c.g] = 1;
    matches.emplace_back(c.e, c.g);
  }
  std::sort(matches.begin(), matches.end());
  std::vector<PosePair> pairs;
  pairs.reserve(matches.size());
  for (const auto& [e, g] : matches)
    pairs.push_back({estimate[e].t_ns, estimate[e].T_world_body, ground_truth[g].T_world_body});
  if (pairs.empty()) {
    return InvalidArgument("no estimated pose has a ground-truth pose within " +
                           std::to_string(static_cast<double>(max_dt_ns) * 1e-6) +
                           " ms (do the trajectories overlap in time, and use the same clock?)");
  }
  return pairs;
}

TrajectoryError EvaluateTrajectory(const std::vector<PosePair>& pairs, Alignment alignment,
                                   double rpe_step_s, int align_num_frames) {
  TrajectoryError e;
  e.pairs = pairs.size();
  e.alignment = Align(pairs, alignment, align_num_frames);
  e.rpe_step_s = rpe_step_s;
  std::vector<double> ate, ate_rot;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PosePair& p = pairs[i];
    ate.push_back((e.alignment.Apply(p.T_world_est.t) - p.T_world_gt.t).norm());
    ate_rot.push_back(RotationDeg(p.T_world_gt.R.transpose() * e.alignment.R * p.T_world_est.R));
    if (i > 0) e.path_length_m += (p.T_world_gt.t - pairs[i - 1].T_world_gt.t).norm();
  }
  e.ate_per_pair_m = ate;
  if (!ate.empty()) {
    e.ate_rmse_m = Rms(ate);
    e.ate_rotation_rmse_deg = Rms(ate_rot);
    double sum = 0.0;
    for (const double x : ate)
      sum += x;
    e.ate_mean_m = sum / static_cast<double>(ate.size());
    e.ate_max_m = *std::max_element(ate.begin(), ate.end());
    std::vector<double> sorted = ate;
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    e.ate_median_m = sorted[sorted.size() / 2];
    const std::size_t used =
        align_num_frames > 0 ? std::min<std::size_t>(pairs.size(), align_num_frames) : pairs.size();
    e.alignment_rotation_sigma_deg =
        AlignmentRotationSigmaDeg(pairs, used, alignment, e.ate_rmse_m);
    e.ate_rotation_rmse_orientation_aligned_deg = OrientationAlignedRotationRmsDeg(pairs);
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
