#pragma once
/// The rectified stereo pair as mapping sees it (docs/conventions.md): one focal length f, the left
/// and right principal points, baseline b. A left pixel (u, v) at inverse depth ρ is the 3-D
/// point p = (u − cx_l, v − cy, f) / (f ρ) in the rectified left camera; it appears in the right
/// camera at u_R = u − f b ρ − (cx_l − cx_r), same row.

#include <Eigen/Core>

#include "aavio/geometry/stereo_rig.hpp"

namespace aavio::mapping {

struct RectifiedStereo {
  int width = 0, height = 0;
  double f = 0.0;  ///< rectified focal length [px]
  double cx_left = 0.0, cx_right = 0.0, cy = 0.0;
  double baseline_m = 0.0;

  static RectifiedStereo FromRig(const geometry::StereoRig& rig) {
    return {rig.width(),    rig.height(), rig.focal_px(),  rig.cx_left(),
            rig.cx_right(), rig.cy(),     rig.baseline_m()};
  }
  double fb() const { return f * baseline_m; }
  /// Disparity u_L − u_R of inverse depth ρ (includes the principal-point offset).
  double Disparity(double rho) const { return fb() * rho + (cx_left - cx_right); }
  double InvDepthOfDisparity(double d) const { return (d - (cx_left - cx_right)) / fb(); }
  Eigen::Vector3d Backproject(double u, double v, double rho) const {
    return Eigen::Vector3d((u - cx_left) / f, (v - cy) / f, 1.0) / rho;
  }
  /// Left-camera projection; false behind the camera.
  bool Project(const Eigen::Vector3d& p, double* u, double* v) const {
    if (p.z() <= 1e-9) return false;
    *u = f * p.x() / p.z() + cx_left;
    *v = f * p.y() / p.z() + cy;
    return true;
  }
};

/// Whether the kind of estimate came from left/right matching or from the AA pair over time.
enum class StereoKind : std::uint8_t { kStatic = 0, kTemporal = 1 };

/// A matched edge pixel with its first inverse depth (before refinement).
struct Match {
  float u = 0.0f, v = 0.0f;  ///< rectified left position
  double rho = 0.0;          ///< inverse depth [1/m]
  double cost = 0.0;         ///< ½(1 − ZNCC) of the match
  StereoKind kind = StereoKind::kStatic;
  bool near_horizontal = false;  ///< the η test put it on a near-horizontal edge
};

}  // namespace aavio::mapping
