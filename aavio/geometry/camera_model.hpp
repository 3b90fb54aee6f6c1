#pragma once
/// Raw (distorted) pinhole camera models, as calibration files describe the sensors:
///   radtan      OpenCV/ROS "plumb_bob": k1 k2 p1 p2 [k3]  (4 or 5 coefficients)
///   equidistant OpenCV fisheye / Kannala–Brandt: k1 k2 k3 k4
/// Coordinates: pixel (u, v) = (column, row), origin at the centre of the top-left pixel;
/// normalised coordinates are (X/Z, Y/Z) in the camera frame (z forward, x right, y down).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::geometry {

enum class DistortionModel { kNone, kRadtan, kEquidistant };

/// The name calibration files use: "none", "plumb_bob", "equidistant".
const char* DistortionModelName(DistortionModel model);

struct CameraIntrinsics {
  int width = 0;                                  ///< image columns [px]
  int height = 0;                                 ///< image rows [px]
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  ///< [px]
  DistortionModel model = DistortionModel::kNone;
  std::vector<double> coeffs;  ///< radtan: k1 k2 p1 p2 [k3]; equidistant: k1 k2 k3 k4
};

class CameraModel {
 public:
  /// Checks sizes, focal lengths, principal point and the coefficient count for the model.
  static Expected<CameraModel> Create(CameraIntrinsics intrinsics);

  const CameraIntrinsics& intrinsics() const { return in_; }
  int width() const { return in_.width; }
  int height() const { return in_.height; }
  DistortionModel model() const { return in_.model; }

  /// Undistorted → distorted normalised coordinates; optionally the 2×2 Jacobian d(out)/d(in).
  Eigen::Vector2d Distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J = nullptr) const;

  /// Distorted → undistorted normalised coordinates by Newton iterations on Distort. Returns
  /// false when it does not converge to 1e-10 (normalised units, ~1e-7 px) within 50 steps.
  bool Undistort(const Eigen::Vector2d& xd, Eigen::Vector2d* xn) const;

  /// Camera-frame point → raw pixel; optionally the 2×3 Jacobian d(pixel)/d(p).
  /// Returns false for points at or behind the camera plane (z <= 1e-9).
  bool Project(const Eigen::Vector3d& p_cam, Eigen::Vector2d* pixel,
               Eigen::Matrix<double, 2, 3>* J = nullptr) const;

  /// Raw pixel → ray (x, y, 1) in the camera frame. False if undistortion does not converge.
  bool Unproject(const Eigen::Vector2d& pixel, Eigen::Vector3d* ray) const;

 private:
  explicit CameraModel(CameraIntrinsics intrinsics) : in_(std::move(intrinsics)) {}
  CameraIntrinsics in_;
};

}  // namespace aavio::geometry
