#pragma once
/// What mapping publishes for tracking: an immutable snapshot of the newest fused map, in world
/// coordinates (shared by pointer; never modified after it is made).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/depth_point.hpp"

namespace aavio::mapping {

struct LocalMap {
  TimeNs t_ns = 0;
  geometry::RigidTransform T_world_ref;       ///< the frame the map was fused in
  std::vector<DepthPoint> points;             ///< in that frame (rectified left pixels, ρ, σ)
  std::vector<Eigen::Vector3d> points_world;  ///< the same points in the world
  /// A bootstrap map or a full, cleaned FIFO's (docs/mapping.md): a depth output. False: a
  /// map of a FIFO not yet cleaned, of unconfirmed estimates, published only for tracking (as
  /// the reference's const_points rule does, or with fusion.publish_while_filling); depth
  /// evaluation, depth files and the cloud skip it.
  bool confirmed = true;
};

using LocalMapPtr = std::shared_ptr<const LocalMap>;

}  // namespace aavio::mapping
