#pragma once
/// Recorded camera paths as simulator input ("twins" of real sequences): cropping, the
/// body → camera rotation, and expressing the path relative to its first camera pose.
///
/// Recorded worlds are taken as z-up (motion capture, DSEC's GNSS/lidar world). The driving rule
/// (for vehicles: DSEC's body frame is the camera turned 180° about its optical axis,
/// shared/data/README.md) picks the camera orientation in the body frame from the motion itself:
/// camera +z along the mean direction of travel, +y toward the ground.

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::sim {

struct CameraPath {
  std::vector<geometry::StampedPose> poses;  ///< camera in the world of its first pose
  Eigen::Vector3d gravity_world;             ///< [m/s²], in that world
  std::string body_to_camera = "identity";   ///< what was applied, in words
};

/// R_body_cam of the driving rule.
Eigen::Matrix3d DrivingBodyToCamera(const std::vector<geometry::StampedPose>& poses);

/// `mode`: identity | driving | auto (driving for paths longer than 20 m at more than 2 m/s).
Expected<CameraPath> CameraPathFromRecording(const std::vector<geometry::StampedPose>& recorded,
                                             double start_s, double duration_s,
                                             const std::string& mode);

}  // namespace aavio::sim
