#pragma once
/// IMU pre-integration between two times (Forster et al., "On-Manifold Preintegration", T-RO
/// 2017; the mid-point discretisation of VINS-Mono): the IMU's rotation ΔR, velocity change Δv and
/// position change Δp over [t_begin, t_end], expressed in the IMU frame at t_begin, with gravity
/// left out, for biases (b_g, b_a) fixed at integration — together with their first-order
/// Jacobians in the biases, so that a new bias estimate corrects them without re-integrating, and
/// the covariance of (δφ, δv, δp) from the sensor's white noise.
///
/// For IMU poses (R_i, p_i), (R_j, p_j) and velocities v_i, v_j in a world with gravity g:
///   R_j = R_i ΔR,   v_j = v_i + g Δt + R_i Δv,   p_j = p_i + v_i Δt + ½ g Δt² + R_i Δp.

#include <Eigen/Core>
#include <span>

#include "aavio/common/status.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

/// White noise densities of the sensor (the continuous-time values of a Kalibr imu.yaml).
struct ImuNoise {
  double gyro_noise_density = 0.00292;  ///< rad/s/√Hz
  double accel_noise_density = 0.044;   ///< m/s²/√Hz
};

struct Preintegrated {
  TimeNs t_begin_ns = 0, t_end_ns = 0;
  double dt_s = 0.0;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  ///< the biases integrated with
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Eigen::Matrix3d delta_R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d delta_v = Eigen::Vector3d::Zero();
  Eigen::Vector3d delta_p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d dR_dbg = Eigen::Matrix3d::Zero();  ///< of Log(ΔR) (right perturbation)
  Eigen::Matrix3d dv_dbg = Eigen::Matrix3d::Zero(), dv_dba = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dp_dbg = Eigen::Matrix3d::Zero(), dp_dba = Eigen::Matrix3d::Zero();
  /// Of (δφ, δv, δp) from the white noise [rad², (m/s)², m²].
  Eigen::Matrix<double, 9, 9> covariance = Eigen::Matrix<double, 9, 9>::Zero();

  /// The terms for other biases, to first order: ΔR·Exp(∂ΔR/∂b_g δb_g), Δv + …, Δp + ….
  Eigen::Matrix3d DeltaR(const Eigen::Vector3d& gyro_bias) const;
  Eigen::Vector3d DeltaV(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias) const;
  Eigen::Vector3d DeltaP(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias) const;
};

/// Readings further apart than this are a gap in the IMU, not integrated across.
inline constexpr TimeNs kMaxSampleGapNs = 50 * kNsPerMs;

/// Pre-integrates time-ordered samples that cover [t_begin, t_end] (a sample at or before
/// t_begin and one at or after t_end, none further apart than kMaxSampleGapNs; OutOfRange
/// otherwise). The readings are interpolated
/// linearly at the interval's ends; each sample interval is integrated at its mid-point readings,
/// the acceleration turned by the mid-point rotation.
Expected<Preintegrated> Preintegrate(std::span<const ImuSample> samples, TimeNs t_begin_ns,
                                     TimeNs t_end_ns, const Eigen::Vector3d& gyro_bias,
                                     const Eigen::Vector3d& accel_bias, const ImuNoise& noise);

}  // namespace aavio::imu
