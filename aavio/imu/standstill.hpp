#pragma once
/// Whether the IMU reads a sensor at rest, over the last kRestSpanS (0.2 s; a tick's ten readings
/// are too few): the mean rate within kRestGyroRadS of the gyroscope's bias (whose estimate may be
/// 0.02 rad/s off after a few seconds of driving straight), the mean specific force gravity alone
/// to within kRestAccelMeanMs2 (not braking hard), its change across the span (a line fitted to
/// the readings) under kRestAccelChange (not starting or swaying), and the readings' variations
/// about their mean integrating to under kRestSpeedChange of velocity at every instant (not
/// shaken by a hand). These are not a spread of readings: they hold for any sample rate and noise
/// density, and a vibration that moves nothing (a drone's idling rotors, a parked car's engine)
/// passes. An IMU alone cannot tell rest from a steady motion, nor a gentle steady braking from
/// rest: the callers add what they know of the speed.

#include <Eigen/Core>
#include <optional>
#include <span>

#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

inline constexpr double kRestGyroRadS = 0.03, kRestAccelMeanMs2 = 0.3, kRestAccelChange = 0.5,
                        kRestSpeedChange = 0.05, kRestSpanS = 0.2;

/// `samples` in time order; the readings over [min(t_begin_ns, t_end_ns − kRestSpanS), t_end_ns]
/// are tested. At rest: their mean specific force (bias removed), else nullopt (also with fewer
/// than two readings there).
std::optional<Eigen::Vector3d> RestReading(std::span<const ImuSample> samples, TimeNs t_begin_ns,
                                           TimeNs t_end_ns, const Eigen::Vector3d& gyro_bias,
                                           const Eigen::Vector3d& accel_bias);

}  // namespace aavio::imu
