#include "aavio/mapping/global_cloud.hpp"

#include <cmath>

namespace aavio::mapping {

void GlobalCloud::Add(const LocalMap& map, double max_depth_m) {
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    if (1.0 / map.points[i].rho > max_depth_m) continue;
    const Eigen::Vector3d& p = map.points_world[i];
    // 21 bits per axis around the origin: ±1e6 voxels.
    auto cell = [&](double x) {
      return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x / voxel_m_)) +
                                        (1 << 20)) &
             0x1fffff;
    };
    const std::uint64_t key = cell(p.x()) << 42 | cell(p.y()) << 21 | cell(p.z());
    if (!occupied_.insert(key).second) continue;
    points_.push_back(p.cast<float>());
    inv_depth_.push_back(static_cast<float>(map.points[i].rho));
  }
}

}  // namespace aavio::mapping
