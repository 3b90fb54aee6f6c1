#pragma once
/// Building blocks of the indoor scenes (scene_builder.hpp): random surface textures and
/// furniture made of boxes. Everything stands on a level floor in the canonical scene frame
/// (x right, y down, z forward); "base" is the centre of an object's footprint.

#include <Eigen/Core>
#include <random>
#include <vector>

#include "aavio/sim/scene.hpp"

namespace aavio::sim {

/// A random texture with edges of every orientation; `cell_lo/hi` set its scale [m]. About a
/// third of the surfaces carry horizontal structure (bricks, level stripes): the case temporal
/// stereo exists for.
Texture RandomTexture(std::mt19937_64& rng, double cell_lo, double cell_hi);

/// Box of `size` (width across `forward`, depth along it, height) standing on `base_centre`.
void AddStandingBox(Scene* scene, const Eigen::Vector3d& base_centre, const Eigen::Vector3d& up,
                    const Eigen::Vector3d& forward, const Eigen::Vector3d& size,
                    const std::vector<Texture>& textures);

/// The six walls of a room [x0, x1] × [y_ceiling, y_floor] × [z0, z1], with `posters` flat
/// pictures a few centimetres off the walls.
void AddRoomShell(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& lo,
                  const Eigen::Vector3d& hi, int posters);

/// Table of `size` (top slab and four legs) with `items` small objects on its top.
/// Returns the height of the top above the floor.
double AddTable(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad,
                const Eigen::Vector3d& size, int items);

/// Open shelf unit: two side panels, `levels` boards (strong level edges) and boxes/books on
/// them; its back to `yaw_rad`.
void AddShelf(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad,
              const Eigen::Vector3d& size, int levels);

/// Sofa: seat, back and two arms.
void AddSofa(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad);

/// Desk-top computer monitor on a stand, facing along −forward(yaw).
void AddMonitor(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad);

/// Serial robot arm: base, a vertical link, a tilted forearm and a gripper.
void AddRobotArm(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad);

}  // namespace aavio::sim
