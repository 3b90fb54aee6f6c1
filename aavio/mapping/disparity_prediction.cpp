#include "aavio/mapping/disparity_prediction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aavio::mapping {

DisparityPrediction::DisparityPrediction(const LocalMap& previous,
                                         const geometry::RigidTransform& T_world_now,
                                         const RectifiedStereo& stereo)
    : cols_((stereo.width + kCellPx - 1) / kCellPx),
      rows_((stereo.height + kCellPx - 1) / kCellPx),
      lo_(static_cast<std::size_t>(cols_) * rows_, std::numeric_limits<float>::max()),
      hi_(lo_.size(), std::numeric_limits<float>::lowest()) {
  const geometry::RigidTransform T_now_world = T_world_now.Inverse();
  for (std::size_t i = 0; i < previous.points_world.size(); ++i) {
    const Eigen::Vector3d p = T_now_world * previous.points_world[i];
    double u, v;
    if (!stereo.Project(p, &u, &v)) continue;
    if (u < 0.0 || v < 0.0 || u >= stereo.width || v >= stereo.height) continue;
    // The point's inverse depth in this view, with its uncertainty scaled by the depth change
    // (σ_ρ ∝ ρ for a given relative depth error).
    const double rho = 1.0 / p.z();
    double sigma_rho = 0.0;
    if (i < previous.points.size() && previous.points[i].rho > 0.0) {
      const DepthPoint& dp = previous.points[i];
      sigma_rho = std::sqrt(std::max(dp.variance(), 0.0)) * rho / dp.rho;
    }
    const double margin = std::max(kMinMarginPx, 3.0 * stereo.fb() * sigma_rho);
    const double d = stereo.Disparity(rho);
    const std::size_t cell = static_cast<std::size_t>(static_cast<int>(v) / kCellPx) * cols_ +
                             static_cast<int>(u) / kCellPx;
    lo_[cell] = std::min(lo_[cell], static_cast<float>(d - margin));
    hi_[cell] = std::max(hi_[cell], static_cast<float>(d + margin));
  }
}

bool DisparityPrediction::Window(float u, float v, const DisparityRange& full,
                                 DisparityRange* window) const {
  const int cu = static_cast<int>(u) / kCellPx, cv = static_cast<int>(v) / kCellPx;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (int r = std::max(0, cv - 1); r <= std::min(rows_ - 1, cv + 1); ++r) {
    for (int c = std::max(0, cu - 1); c <= std::min(cols_ - 1, cu + 1); ++c) {
      const std::size_t cell = static_cast<std::size_t>(r) * cols_ + c;
      lo = std::min(lo, lo_[cell]);
      hi = std::max(hi, hi_[cell]);
    }
  }
  if (lo > hi) return false;
  window->min = std::max(full.min, static_cast<int>(std::floor(lo)));
  window->max = std::min(full.max, static_cast<int>(std::ceil(hi)));
  return window->min <= window->max;
}

int DisparityPrediction::covered_cells() const {
  int n = 0;
  for (std::size_t i = 0; i < lo_.size(); ++i)
    n += lo_[i] <= hi_[i] ? 1 : 0;
  return n;
}

}  // namespace aavio::mapping
