#include "aavio/mapping/out_of_view_check.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core/mat.hpp>

namespace aavio::mapping {

void DropOutOfViewMatches(const LocalMap& previous, const geometry::RigidTransform& T_world_now,
                          const RectifiedStereo& stereo, int patch_half_width, int radius_px,
                          std::vector<Match>* matches) {
  constexpr double kFartherFactor = 0.8;  // the match's disparity below 80 % of the surface's
  const int w = stereo.width, h = stereo.height;
  // The nearest previous-map surface per pixel of the current view (inverse depth, 0 = none).
  cv::Mat nearest(h, w, CV_32FC1, cv::Scalar(0.0f));
  const geometry::RigidTransform T_now_world = T_world_now.Inverse();
  for (const Eigen::Vector3d& p_world : previous.points_world) {
    const Eigen::Vector3d p = T_now_world * p_world;
    double u, v;
    if (!stereo.Project(p, &u, &v)) continue;
    const int iu = static_cast<int>(std::lround(u)), iv = static_cast<int>(std::lround(v));
    if (iu < 0 || iv < 0 || iu >= w || iv >= h) continue;
    float& cell = nearest.at<float>(iv, iu);
    cell = std::max(cell, static_cast<float>(1.0 / p.z()));
  }
  std::erase_if(*matches, [&](const Match& m) {
    const int u = static_cast<int>(std::lround(m.u)), v = static_cast<int>(std::lround(m.v));
    float rho_near = 0.0f;
    for (int y = std::max(0, v - radius_px); y <= std::min(h - 1, v + radius_px); ++y) {
      const float* row = nearest.ptr<float>(y);
      for (int x = std::max(0, u - radius_px); x <= std::min(w - 1, u + radius_px); ++x)
        rho_near = std::max(rho_near, row[x]);
    }
    if (rho_near <= 0.0f) return false;  // nothing known here
    const double d_near = stereo.Disparity(static_cast<double>(rho_near));
    const bool out_of_view = static_cast<double>(m.u) - d_near - patch_half_width < 1.0;
    return out_of_view && stereo.Disparity(m.rho) < kFartherFactor * d_near;
  });
}

}  // namespace aavio::mapping
