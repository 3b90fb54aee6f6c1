#include "aavio/eval/velocity_error.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::eval {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

VelocityError EvaluateVelocities(const std::vector<geometry::StampedVelocity>& estimate,
                                 const std::vector<geometry::StampedVelocity>& ground_truth,
                                 TimeNs max_dt_ns) {
  VelocityError e;
  std::vector<double> rve, weight, speeds;
  double linear2 = 0.0, angular2 = 0.0;
  std::size_t g = 0;
  for (const geometry::StampedVelocity& est : estimate) {
    if (!est.valid) continue;
    while (g + 1 < ground_truth.size() && ground_truth[g + 1].t_ns <= est.t_ns)
      ++g;
    // The nearer of the ground-truth velocities just before and after.
    std::size_t best = ground_truth.size();
    TimeNs best_dt = max_dt_ns + 1;
    for (std::size_t k = g; k < std::min(g + 2, ground_truth.size()); ++k) {
      const TimeNs dt = std::llabs(ground_truth[k].t_ns - est.t_ns);
      if (ground_truth[k].valid && dt < best_dt) best = k, best_dt = dt;
    }
    if (best == ground_truth.size()) continue;
    const geometry::StampedVelocity& gt = ground_truth[best];
    const double speed = gt.v_body_mps.norm();
    const double diff = (gt.v_body_mps - est.v_body_mps).norm();
    rve.push_back(speed > 0.0 ? diff / speed : 0.0);
    weight.push_back(speed);
    speeds.push_back(speed);
    linear2 += diff * diff;
    angular2 += (gt.w_body_radps - est.w_body_radps).squaredNorm();
  }
  e.pairs = rve.size();
  if (e.pairs == 0) return e;
  const double n = static_cast<double>(e.pairs);
  e.linear_rmse_mps = std::sqrt(linear2 / n);
  e.angular_rmse_dps = std::sqrt(angular2 / n) * 180.0 / M_PI;
  e.rve_median = Median(rve);
  e.gt_speed_median_mps = Median(speeds);
  double total = 0.0;
  for (const double w : weight)
    total += w;
  if (total <= 0.0) return e;
  // S(ξ) at ξ_k = k / 499, k = 0 … 499, then the trapezoid rule.
  constexpr int kPoints = 500;
  std::vector<std::size_t> order(rve.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return rve[a] < rve[b]; });
  std::vector<double> success(kPoints);
  double below = 0.0;
  std::size_t next = 0;
  for (int k = 0; k < kPoints; ++k) {
    const double xi = static_cast<double>(k) / (kPoints - 1);
    while (next < order.size() && rve[order[next]] < xi)
      below += weight[order[next++]];
    success[k] = below / total;
  }
  for (int k = 1; k < kPoints; ++k)
    e.auc += 0.5 * (success[k] + success[k - 1]) / (kPoints - 1);
  return e;
}

}  // namespace aavio::eval
