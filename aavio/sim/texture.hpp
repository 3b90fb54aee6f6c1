#pragma once
/// Procedural textures for the simulator's surfaces, evaluated in O(1) and anti-aliased
/// analytically: every pattern is built from step edges whose coverage over a pixel's footprint
/// w is clamp(0.5 + d / w, 0, 1) for the signed distance d to the edge — the box-filtered step,
/// so edges do not alias into false events. Cell albedos come from a hash of the cell and the
/// texture's seed, so a scene is deterministic from its seed.

#include <cstdint>
#include <limits>

namespace aavio::sim {

enum class Pattern {
  kBricks,   ///< staggered bricks: long horizontal mortar lines, short vertical ones
  kTiles,    ///< square tiles of random albedo (edges along both axes)
  kStripes,  ///< parallel bands of random albedo at the texture's angle
  kBlobs,    ///< discs on a jittered grid (edges of every orientation)
  kWindows,  ///< facade: rows of windows with sills (strongly horizontal)
};

struct Texture {
  Pattern pattern = Pattern::kTiles;
  double cell_m = 0.3;     ///< characteristic size of the pattern [m]
  double angle_rad = 0.0;  ///< rotation of the pattern in the surface
  double contrast = 0.6;   ///< spread of albedos around the mean
  double mean = 0.5;       ///< mean albedo
  std::uint64_t seed = 0;

  /// Albedo in (0, 1] at surface coordinates (u, v) [m], box-filtered over a footprint [m].
  /// Reads only: safe to call from several threads.
  double Albedo(double u_m, double v_m, double footprint_m) const;

  /// Caches cos/sin of angle_rad (Scene::Build calls it); Albedo works without it, slower.
  void Prepare();

 private:
  double cos_ = 1.0, sin_ = 0.0, prepared_angle_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace aavio::sim
