#pragma once
/// An observation with the pose of the camera that made it: what mapping works on.

#include <memory>

#include "aavio/events/observation.hpp"
#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::mapping {

struct PosedObservation {
  std::shared_ptr<const events::Observation> obs;
  geometry::RigidTransform T_world_obs;
};

}  // namespace aavio::mapping
