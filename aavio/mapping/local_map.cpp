#include "aavio/mapping/local_map.hpp"

namespace aavio::mapping {

std::vector<Eigen::Vector3d> PointsForTracking(const LocalMap& map, const FusionConfig& fusion) {
  if (fusion.track_unconfirmed_temporal || !map.confirmed) return map.points_world;
  std::vector<Eigen::Vector3d> kept;
  kept.reserve(map.points_world.size());
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    const DepthPoint& p = map.points[i];
    if (p.kind == StereoKind::kTemporal && p.age < fusion.min_age) continue;
    kept.push_back(map.points_world[i]);
  }
  return kept;
}

}  // namespace aavio::mapping
