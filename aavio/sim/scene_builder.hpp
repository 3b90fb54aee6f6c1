#pragma once
/// The built-in scenes (issue 4), deterministic from a seed. All are in the world frame of
/// motions.hpp: gravity along +y ("down" is +y), the first camera at the origin looking along +z.

#include <vector>

#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/sim/scene.hpp"

namespace aavio::sim {

enum class SceneKind { kRoom, kOffice, kLab, kHall, kStreet, kPlanes };

/// rpg-like room: walls ~3 m around the start, floor 1.3 m below the camera, posters and boxes
/// 0.5–4 m from the start position.
Scene BuildRoom(std::uint64_t seed);
/// Office around a desk (TUM-VIE's mocap desk): the desk 0.7–1.5 m ahead with a monitor, books
/// and boxes, bookshelves behind it, a side table and a cabinet; the floor 1 m below the camera.
Scene BuildOffice(std::uint64_t seed);
/// Lab (VECtor's mocap room): a workbench, a robot arm on a table, a sofa, shelves, a cabinet
/// and crates in a 7 × 3 × 6 m room.
Scene BuildLab(std::uint64_t seed);
/// MVSEC-like hall: 20 × 8 × 20 m with pillars and crates.
Scene BuildHall(std::uint64_t seed);
/// DSEC-like street canyon laid along `path` (camera positions; `down` = gravity direction):
/// road with markings, facades 6–15 m to each side with windows and ledges, poles, parked cars.
Scene BuildStreet(const std::vector<geometry::StampedPose>& path, const Eigen::Vector3d& down,
                  double camera_height_m, std::uint64_t seed);

/// A sparse scene of a few textured planes, unlike the furnished ones: a back wall 3.5 m ahead,
/// two free-standing panels 1.6–2.6 m ahead, and the floor 1 m below the camera, each with a
/// coarse, low-contrast pattern (cells of 0.25–0.6 m): 1–4 events per pixel per second at the
/// planes preset's motion, a tenth of the rooms'.
Scene BuildPlanes(std::uint64_t seed);

/// The scene of `kind`; the street is laid along `path` (the others ignore it, `down` and
/// `camera_height_m`).
Scene BuildScene(SceneKind kind, const std::vector<geometry::StampedPose>& path,
                 const Eigen::Vector3d& down, double camera_height_m, std::uint64_t seed);

}  // namespace aavio::sim
