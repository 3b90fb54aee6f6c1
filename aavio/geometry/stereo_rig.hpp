#pragma once
/// A calibrated, rectified stereo pair of event cameras (docs/conventions.md, docs/conventions.md).
///
/// Frames: `left`/`right` are the raw (distorted) cameras; `rect_left`/`rect_right` the rectified
/// ones, R_rect_left_left maps raw-left coordinates into the rectified-left frame. All 3D maths of
/// the pipeline happens in the rectified left frame, with the rectified projections
///   P_left  = K' [I | 0],   P_right = K'_R [I | (−b, 0, 0)ᵀ]   (so P_right(0,3) = −f b < 0).
/// The IMU extrinsic is T_imu_left: p_imu = T_imu_left · p_left (ESVO2's `T_b_c` of left.yaml).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/camera_model.hpp"
#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::geometry {

using ProjectionMatrix = Eigen::Matrix<double, 3, 4>;

struct StereoRigParams {
  CameraModel left;
  CameraModel right;
  Eigen::Matrix3d R_rect_left_left;          ///< rectification rotation of the left camera
  Eigen::Matrix3d R_rect_right_right;        ///< rectification rotation of the right camera
  ProjectionMatrix P_left;                   ///< rectified left projection
  ProjectionMatrix P_right;                  ///< rectified right projection, P(0,3) = −f b
  RigidTransform T_right_left;               ///< raw right ← raw left
  std::optional<RigidTransform> T_imu_left;  ///< IMU ← raw left camera; empty if not calibrated
};

class StereoRig {
 public:
  /// Validates and builds the rig. Rotations are accepted up to 1e-3 from orthonormal (files
  /// print 6 digits) and then re-orthonormalised. Non-fatal findings (e.g. T_right_left slightly
  /// inconsistent with the rectification) are appended to `warnings`.
  static Expected<StereoRig> Create(StereoRigParams params,
                                    std::vector<std::string>* warnings = nullptr);

  const CameraModel& left() const { return p_.left; }
  const CameraModel& right() const { return p_.right; }
  int width() const { return p_.left.width(); }
  int height() const { return p_.left.height(); }

  const Eigen::Matrix3d& R_rect_left_left() const { return p_.R_rect_left_left; }
  const Eigen::Matrix3d& R_rect_right_right() const { return p_.R_rect_right_right; }
  const ProjectionMatrix& P_left() const { return p_.P_left; }
  const ProjectionMatrix& P_right() const { return p_.P_right; }
  const RigidTransform& T_right_left() const { return p_.T_right_left; }
  const std::optional<RigidTransform>& T_imu_left() const { return p_.T_imu_left; }

  double focal_px() const { return p_.P_left(0, 0); }  ///< rectified focal length f
  double cx_left() const { return p_.P_left(0, 2); }
  double cx_right() const { return p_.P_right(0, 2); }
  double cy() const { return p_.P_left(1, 2); }
  /// b = ‖P_R[:, :3]⁻¹ P_R[:, 3]‖ (docs/conventions.md).
  double baseline_m() const { return baseline_m_; }

  /// Rectified right ← rectified left: a pure translation (−b, 0, 0).
  RigidTransform T_rect_right_rect_left() const;
  /// IMU ← rectified left camera, the frame tracking estimates; empty if no IMU extrinsic.
  std::optional<RigidTransform> T_imu_rect_left() const;

  /// The same rig with the right camera moved along the baseline so that it is `baseline_m` long
  /// (T_right_left's translation and P_right's last column scaled; everything else kept).
  Expected<StereoRig> WithBaseline(double baseline_m) const;

  /// Disparity u_L − u_R of a point at depth z [m] in the rectified pair (includes the
  /// principal-point offset cx_L − cx_R of rigs rectified without zero disparity).
  double DisparityAtDepth(double depth_m) const;

 private:
  explicit StereoRig(StereoRigParams params, double baseline_m)
      : p_(std::move(params)), baseline_m_(baseline_m) {}
  StereoRigParams p_;
  double baseline_m_;
};

}  // namespace aavio::geometry
