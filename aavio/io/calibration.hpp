#pragma once
/// Loading a stereo calibration into a StereoRig. Supported layouts (docs/io.md):
///   ESVO/ESVO2 YAML   a folder with left.yaml + right.yaml (ROS camera_info style plus
///                     T_right_left and, for the IMU, T_b_c), or either of the two files;
///   DSEC              cam_to_cam.yaml, or a sequence folder holding calibration/cam_to_cam.yaml.

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/stereo_rig.hpp"

namespace aavio::io {

struct LoadedCalibration {
  geometry::StereoRig rig;
  std::string format;                 ///< "esvo" or "dsec"
  std::vector<std::string> files;     ///< the files read
  std::vector<std::string> warnings;  ///< non-fatal findings, for the user to see
};

/// ESVO/ESVO2 left.yaml + right.yaml.
///
/// T_right_left (3x4, read from left.yaml) maps raw-left into raw-right coordinates. Rule for
/// files whose T_right_left declares 3x4 but holds 9 numbers (ESVO2's DSEC calibration) or that
/// have none: the extrinsic is derived from the rectification, T_right_left =
/// [R_rect_rightᵀ R_rect_left | R_rect_rightᵀ (−b, 0, 0)ᵀ] with b from P_right, and a warning
/// says so (for 9 numbers it also reports their angle to the derived rotation).
/// T_b_c (3x4, optional, left.yaml) is camera → IMU: p_imu = R p_cam + t.
Expected<LoadedCalibration> LoadEsvoCalibration(const std::string& left_yaml,
                                                const std::string& right_yaml);

/// DSEC cam_to_cam.yaml: cam0 (left event camera) and cam3 (right event camera), camRect0/3,
/// R_rect0/3, T_10·T_21·T_32 chained to T_30 and the baseline b = 1/Q[3][2] of cams_03. The
/// file's internal relations R_rect3·R_30·R_rect0ᵀ = I and R_rect3·t_30 = (−b, 0, 0) are checked.
Expected<LoadedCalibration> LoadDsecCalibration(const std::string& cam_to_cam_yaml);

/// Detects the layout of `path` (a file or a folder, as above) and loads it.
Expected<LoadedCalibration> LoadCalibration(const std::string& path);

}  // namespace aavio::io

namespace aavio::io {

/// Writes `rig` as ESVO/ESVO2 left.yaml + right.yaml into `folder` (created if needed), with
/// T_right_left and, when the rig has an IMU extrinsic, T_b_c (= T_imu_left). Reading the folder
/// back with LoadCalibration gives the same rig.
Status WriteEsvoCalibration(const std::string& folder, const geometry::StereoRig& rig,
                            const std::string& camera_name = "aavio_sim");

}  // namespace aavio::io
