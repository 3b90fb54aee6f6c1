#pragma once
/// Where the previous map says a stereo match lies (aavio). The published map, moved into the
/// current left view, predicts each edge pixel's disparity; static stereo's row search and
/// temporal stereo's epipolar search then only need a window around the prediction instead of the
/// whole depth range (on the DSEC rig 80+ disparities per pixel). The window is as wide as the map
/// points' own uncertainty (3σ of their inverse depth, at least kMinMarginPx) and spans every
/// point near the pixel, so a depth edge keeps both of its sides. Pixels the map knows nothing
/// about are searched in full.

#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/local_map.hpp"
#include "aavio/mapping/rectified_stereo.hpp"
#include "aavio/mapping/static_stereo.hpp"

namespace aavio::mapping {

class DisparityPrediction {
 public:
  /// Cells of this many pixels collect the projected points; a pixel's window spans the points of
  /// its cell and the 8 around it (so points 8–16 px away count).
  static constexpr int kCellPx = 8;
  /// The narrowest half window [px]: matching is to the whole pixel, and the map's pose and the
  /// current one are estimates too.
  static constexpr double kMinMarginPx = 2.0;

  /// The map `previous` in the view at T_world_now.
  DisparityPrediction(const LocalMap& previous, const geometry::RigidTransform& T_world_now,
                      const RectifiedStereo& stereo);

  /// The disparity window the map predicts at rectified left pixel (u, v), inside `full`; false
  /// where no map point is near.
  bool Window(float u, float v, const DisparityRange& full, DisparityRange* window) const;

  /// Cells with a prediction (for tests).
  int covered_cells() const;

 private:
  int cols_ = 0, rows_ = 0;
  std::vector<float> lo_, hi_;  // per cell; lo_ > hi_ where nothing was projected
};

}  // namespace aavio::mapping
