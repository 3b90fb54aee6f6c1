#include "aavio/eval/relative_error.hpp"

#include <algorithm>
#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// The index j ≥ i whose distance is closest to `target`, the first of equals (rpg's
// compute_comparison_indices_length scans forward keeping strict improvements), or −1 when the
// closest is not within `tolerance`.
std::ptrdiff_t EndIndex(const std::vector<double>& d, std::size_t i, double target, double tolerance) {
  const auto begin = d.begin() + static_cast<std::ptrdiff_t>(i);
  auto above = std::lower_bound(begin, d.end(), target);
  std::ptrdiff_t best = -1;
  double best_error = tolerance;
  if (above != begin) {
    // the first index holding the value just below the target
    const auto below = std::lower_bound(begin, above, *(above - 1));
    const double error = std::abs(*below - target);
    if (error < best_error) {
      best_error = error;
      best = below - d.begin();
    }
  }
  if (above != d.end() && std::abs(*above - target) < best_error) best = above - d.begin();
  return best;
}

}  // namespace

Status RelativeErrorConfig::Validate() const {
  for (const double f : fractions)
    if (!(f > 0.0 && f <= 1.0))
      return InvalidArgument("relative error: fractions must be in (0, 1], got " + std::to_string(f));
  for (const double l : lengths_m)
    if (!(l > 0.0)) return InvalidArgument("relative error: lengths must be > 0 m");
  if (fractions.empty() && lengths_m.empty())
    return InvalidArgument("relative error: give sub-trajectory fractions or lengths");
  if (!(max_length_error_fraction > 0.0 && max_length_error_fraction < 1.0))
    return InvalidArgument("relative error: max_length_error_fraction must be in (0, 1)");
  return Status::Ok();
}

std::vector<double> DistanceFromStart(const std::vector<PosePair>& pairs) {
  std::vector<double> d(pairs.size(), 0.0);
  for (std::size_t i = 1; i < pairs.size(); ++i)
    d[i] = d[i - 1] + (pairs[i].T_world_gt.t - pairs[i - 1].T_world_gt.t).norm();
  return d;
}

RelativeError ComputeRelativeError(const std::vector<PosePair>& pairs, double path_length_m,
                                   double scale, const RelativeErrorConfig& config) {
  RelativeError result;
  std::vector<double> lengths = config.lengths_m;
  if (lengths.empty())
    for (const double f : config.fractions)
      lengths.push_back(std::trunc(f * path_length_m * 100.0) / 100.0);
  const std::vector<double> d = DistanceFromStart(pairs);
  double sum_pct = 0.0, sum_deg_per_m = 0.0;
  for (const double L : lengths) {
    SubTrajectoryErrors s;
    s.length_m = L;
    if (L > 0.0) {
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const std::ptrdiff_t j =
            EndIndex(d, i, d[i] + L, config.max_length_error_fraction * L);
        if (j < 0) continue;
        const PosePair& a = pairs[i];
        const PosePair& b = pairs[static_cast<std::size_t>(j)];
        geometry::RigidTransform E = a.T_world_est.Inverse() * b.T_world_est;
        E.t *= scale;
        const geometry::RigidTransform G = a.T_world_gt.Inverse() * b.T_world_gt;
        const geometry::RigidTransform delta = G.Inverse() * E;
        // in the estimate's world orientation at the end (rpg's T_error_in_w)
        const Eigen::Matrix3d& R_end = b.T_world_est.R;
        const Eigen::Matrix3d R_w = R_end * delta.R * R_end.transpose();
        const Eigen::Vector3d t_w = R_end * delta.t;
        const double trans = t_w.norm();
        const double rot = geometry::LogSO3(delta.R).norm() * kRadToDeg;
        s.start_distance_m.push_back(d[i]);
        s.trans_m.push_back(trans);
        s.trans_pct.push_back(trans / L * 100.0);
        s.rot_deg.push_back(rot);
        s.rot_deg_per_m.push_back(rot / L);
        s.yaw_deg.push_back(std::abs(std::atan2(R_w(1, 0), R_w(0, 0))) * kRadToDeg);
      }
    }
    if (s.trans_m.size() < 2) {  // rpg: "Too few samples! Will not compute."
      s = SubTrajectoryErrors{};
      s.length_m = L;
    }
    s.trans_m_stats = ComputeStatistics(s.trans_m);
    s.trans_pct_stats = ComputeStatistics(s.trans_pct);
    s.rot_deg_stats = ComputeStatistics(s.rot_deg);
    s.rot_deg_per_m_stats = ComputeStatistics(s.rot_deg_per_m);
    s.yaw_deg_stats = ComputeStatistics(s.yaw_deg);
    for (std::size_t k = 0; k < s.trans_pct.size(); ++k) {
      sum_pct += s.trans_pct[k] * s.trans_pct[k];
      sum_deg_per_m += s.rot_deg_per_m[k] * s.rot_deg_per_m[k];
    }
    result.samples += s.trans_pct.size();
    result.per_length.push_back(std::move(s));
  }
  if (result.samples > 0) {
    result.trans_pct_rmse = std::sqrt(sum_pct / static_cast<double>(result.samples));
    result.rot_deg_per_m_rmse = std::sqrt(sum_deg_per_m / static_cast<double>(result.samples));
  }
  return result;
}

}  // namespace aavio::eval
