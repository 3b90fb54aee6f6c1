#pragma once
/// The built-in scenes (issue 4), deterministic from a seed. All are in the world frame of
/// motions.hpp: gravity along +y ("down" is +y), the first camera at the origin looking along +z.

#include <vector>

#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/sim/scene.hpp"

namespace aavio::sim {

/// rpg-like room: walls ~3 m around the start, floor 1.3 m below the camera, posters and boxes
/// 0.5–4 m from the start position.
Scene BuildRoom(std::uint64_t seed);
/// MVSEC-like hall: 20 × 8 × 20 m with pillars and crates.
Scene BuildHall(std::uint64_t seed);
/// DSEC-like street canyon laid along `path` (camera positions; `down` = gravity direction):
/// road with markings, facades 6–15 m to each side with windows and ledges, poles, parked cars.
Scene BuildStreet(const std::vector<geometry::StampedPose>& path, const Eigen::Vector3d& down,
                  double camera_height_m, std::uint64_t seed);

}  // namespace aavio::sim
