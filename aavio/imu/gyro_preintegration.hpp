#pragma once
/// Gyroscope pre-integration between two ticks (docs/tracking.md): the relative rotation of the
/// IMU from t_begin to t_end by mid-point quaternion integration of (ω̃ − b_g), with the first and
/// last sample intervals clipped to [t_begin, t_end], and the same rotation expressed in the
/// camera.
///
/// Convention (one, used everywhere): `R_imu_cam` maps camera coordinates to IMU coordinates,
/// p_imu = R_imu_cam p_cam — the rotation of StereoRig::T_imu_rect_left (ESVO2's T_b_c). A body
/// rotation ΔR_imu (the IMU frame at t_end in the IMU frame at t_begin) is, for the camera,
/// ΔR_cam = R_imu_camᵀ ΔR_imu R_imu_cam.

#include <Eigen/Core>
#include <span>

#include "aavio/common/status.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

/// ΔR_imu over [t_begin, t_end] from time-ordered samples that cover the interval (a sample at or
/// before t_begin and one at or after t_end); OutOfRange otherwise.
Expected<Eigen::Matrix3d> IntegrateGyro(std::span<const ImuSample> samples, TimeNs t_begin,
                                        TimeNs t_end, const Eigen::Vector3d& gyro_bias);

/// ΔR_cam = R_imu_camᵀ ΔR_imu R_imu_cam: the camera at t_end in the camera at t_begin.
Eigen::Matrix3d ImuToCameraRotation(const Eigen::Matrix3d& delta_R_imu,
                                    const Eigen::Matrix3d& R_imu_cam);

/// The mean gyroscope reading over [t_begin, t_end] (a bias estimate for a static interval).
Expected<Eigen::Vector3d> MeanGyro(std::span<const ImuSample> samples, TimeNs t_begin,
                                   TimeNs t_end);

}  // namespace aavio::imu
