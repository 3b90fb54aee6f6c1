#pragma once
/// What real worlds have and a static, steadily lit scene lacks, each an effect that can be
/// switched on alone (`aavio simulate --world-effects flicker,moving_objects`):
///
/// - **flicker**: light sources in view whose radiance follows the mains — 100 Hz (50 Hz mains)
///   or 120 Hz (60 Hz), one per sequence, each lamp on one of the three phases — with a
///   modulation depth from 0.3 (fluorescent tubes, incandescent bulbs) to 0.95 (LED drivers
///   and traffic lights). Lamps are placed on the surfaces the camera looks at along its path,
///   each 3–10 % of the image wide, so that several are in view at any time.
/// - **moving_objects**: things that move on their own through the view, one every ~3 s of the
///   sequence — in a street, oncoming cars in the other lane (8–14 m/s) and cyclists crossing
///   ahead; elsewhere, people walking past across the view (1.0–1.6 m/s), half-way between the
///   camera and what it looks at, a third of the image wide or more. Each is a textured box
///   standing on the ground and translating at constant velocity.
///
/// Both are placed from the camera's path and the scene itself, so they work on any scene,
/// built-in motion or recorded trajectory; the same seed gives the same world.

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/sim/scene.hpp"

namespace aavio::sim {

struct WorldEffect {
  const char* name;
  const char* description;
};
const std::vector<WorldEffect>& WorldEffects();

/// OK if every name is a world effect; else an error naming the ones there are.
Status CheckWorldEffectNames(const std::vector<std::string>& names);

struct WorldEffectPlacement {
  /// The camera (optical axis +z) in the world, over the sequence.
  std::vector<geometry::StampedPose> camera_path;
  Eigen::Vector3d gravity_world = Eigen::Vector3d::UnitY();
  double half_fov_rad = 0.5;  ///< horizontal
  bool street = false;        ///< cars and cyclists rather than people
  std::uint64_t seed = 1;
};

/// What the effects added, in words.
struct WorldEffectsAdded {
  int lights = 0;
  double flicker_hz = 0.0;
  int moving_objects = 0;
  std::string Describe() const;
};

/// Adds the named effects' quads to `scene` (which must be built: placement casts rays into
/// it) and rebuilds it; `scene.time_origin_ns` becomes the path's first stamp.
WorldEffectsAdded AddWorldEffects(const std::vector<std::string>& names,
                                  const WorldEffectPlacement& placement, Scene* scene);

}  // namespace aavio::sim
