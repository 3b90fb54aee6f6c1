#pragma once
/// Recorded camera paths as simulator input ("twins" of real sequences): cropping, removing the
/// measurement noise (path_smoothing.hpp), the body → camera rotation, and expressing the path
/// relative to its first camera pose.
///
/// The driving rule (for vehicles, whose recorded body frame need not be the camera's — DSEC's is
/// the camera turned about its optical axis, shared/data/README.md) picks the camera orientation
/// in the body frame from the motion itself: camera +z along the mean direction of travel, +y
/// along the path plane's normal (or the body's own vertical axis on a straight path). Which
/// side of the plane is "down" is not observable from positions: the sign is a convention
/// (DrivingBodyToCamera), and the simulator builds the ground on that side, so the twin is
/// consistent. Gravity lies along the first camera's +y: the ground side for vehicles, and the
/// upright start of a hand-held camera (recorded worlds need not be gravity-aligned).

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::sim {

struct CameraPath {
  std::vector<geometry::StampedPose> poses;  ///< camera in the world of its first pose
  Eigen::Vector3d gravity_world;             ///< [m/s²], in that world
  std::string body_to_camera = "identity";   ///< what was applied, in words
  std::string smoothing;                     ///< the measurement noise removed, in words
};

/// R_body_cam of the driving rule.
Eigen::Matrix3d DrivingBodyToCamera(const std::vector<geometry::StampedPose>& poses);

/// `mode`: identity | driving | auto (driving for recordings longer than 20 m at more than
/// 2 m/s). The vehicle test and the rule use the whole recording; the crop follows.
Expected<CameraPath> CameraPathFromRecording(const std::vector<geometry::StampedPose>& recorded,
                                             double start_s, double duration_s,
                                             const std::string& mode);

}  // namespace aavio::sim
