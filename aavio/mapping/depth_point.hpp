#pragma once
/// An inverse-depth estimate with its Student-t uncertainty (docs/mapping.md).

#include <Eigen/Core>

#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::mapping {

struct DepthPoint {
  float u = 0.0f, v = 0.0f;  ///< rectified left position in its frame
  double rho = 0.0;          ///< inverse depth [1/m]
  double s2 = 0.0;           ///< Student-t scale² of ρ [1/m²]
  double nu = 3.0;           ///< Student-t degrees of freedom (> 2)
  double residual = 0.0;     ///< cost of its refinement (robustified, Σ w r²)
  int age = 0;               ///< fusions it has been through
  int batch = -1;            ///< fusion FIFO batch that last contributed to it (-1: none)
  StereoKind kind = StereoKind::kStatic;
  bool near_horizontal = false;

  /// σ² = ν/(ν − 2) s².
  double variance() const { return nu > 2.0 ? nu / (nu - 2.0) * s2 : s2; }
  Eigen::Vector3d Point(const RectifiedStereo& stereo) const {
    return stereo.Backproject(u, v, rho);
  }
};

}  // namespace aavio::mapping
