#include "aavio/sim/imu_synthesis.hpp"

#include <cmath>
#include <random>

#include "aavio/common/config_fields.hpp"
#include "aavio/geometry/random_draws.hpp"

namespace aavio::sim {

ImuNoiseModel ImuNoiseModel::Perfect() {
  ImuNoiseModel m;
  m.gyro_noise_density = m.accel_noise_density = 0.0;
  m.gyro_random_walk = m.accel_random_walk = 0.0;
  m.gyro_bias = {0.0, 0.0, 0.0};
  m.accel_bias = {0.0, 0.0, 0.0};
  return m;
}

ImuNoiseModel ImuNoiseModel::Datasheet() {
  constexpr double kPi = 3.14159265358979323846;
  ImuNoiseModel m;
  m.gyro_noise_density = 0.005 * kPi / 180.0;  // 8.73e-5 rad/s/√Hz
  m.accel_noise_density = 400e-6 * 9.80665;    // 3.92e-3 m/s²/√Hz
  return m;
}

Status ImuNoiseModel::Validate() const {
  FieldChecker check;
  check.InRange("rate_hz", rate_hz, 1.0, 100000.0)
      .NonNegative("gyro_noise_density", gyro_noise_density)
      .NonNegative("accel_noise_density", accel_noise_density)
      .NonNegative("gyro_random_walk", gyro_random_walk)
      .NonNegative("accel_random_walk", accel_random_walk);
  for (int k = 0; k < 3; ++k) {
    check.InRange("gyro_bias", gyro_bias[k], -1.0, 1.0)
        .InRange("accel_bias", accel_bias[k], -5.0, 5.0);
  }
  return check.status();
}

Expected<std::vector<imu::ImuSample>> SynthesizeImu(const MotionSpline& spline,
                                                    const geometry::RigidTransform& T_imu_body,
                                                    const Eigen::Vector3d& gravity_world,
                                                    const ImuNoiseModel& model,
                                                    std::uint64_t seed) {
  AAVIO_RETURN_IF_ERROR(model.Validate());
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto noise = [&] { return geometry::DrawZyx(normal, rng); };

  const double dt = 1.0 / model.rate_hz;
  const double gyro_sigma = model.gyro_noise_density * std::sqrt(model.rate_hz);
  const double accel_sigma = model.accel_noise_density * std::sqrt(model.rate_hz);
  const double gyro_walk = model.gyro_random_walk * std::sqrt(dt);
  const double accel_walk = model.accel_random_walk * std::sqrt(dt);
  Eigen::Vector3d gyro_bias(model.gyro_bias.data());
  Eigen::Vector3d accel_bias(model.accel_bias.data());

  // The IMU sits at p_body_imu in the body frame: its acceleration adds the lever-arm terms
  // α × r + ω × (ω × r) (α by central difference of the analytic ω).
  const geometry::RigidTransform T_body_imu = T_imu_body.Inverse();
  const Eigen::Vector3d& r_body = T_body_imu.t;
  const Eigen::Matrix3d& R_imu_body = T_imu_body.R;
  const TimeNs step_ns = SecondsToNs(dt);
  const TimeNs h_ns = 100'000;  // 0.1 ms for α

  std::vector<imu::ImuSample> samples;
  samples.reserve(static_cast<std::size_t>((spline.t_end_ns() - spline.t_begin_ns()) / step_ns) +
                  1);
  for (std::int64_t k = 0;; ++k) {
    const TimeNs t = spline.t_begin_ns() + SecondsToNs(static_cast<double>(k) * dt);
    if (t > spline.t_end_ns()) break;
    const Eigen::Matrix3d R_world_body = spline.Rotation(t);
    const Eigen::Vector3d omega_body = spline.AngularVelocity(t);
    Eigen::Vector3d accel_body_origin_world = spline.LinearAcceleration(t);
    Eigen::Vector3d lever = Eigen::Vector3d::Zero();
    if (r_body.squaredNorm() > 0.0) {
      const TimeNs t0 = std::max(spline.t_begin_ns(), t - h_ns);
      const TimeNs t1 = std::min(spline.t_end_ns(), t + h_ns);
      const Eigen::Vector3d alpha =
          (spline.AngularVelocity(t1) - spline.AngularVelocity(t0)) / NsToSeconds(t1 - t0);
      lever = alpha.cross(r_body) + omega_body.cross(omega_body.cross(r_body));
    }
    // Specific force: what an accelerometer at rest reads is −g, i.e. "up".
    const Eigen::Vector3d specific_force_body =
        R_world_body.transpose() * (accel_body_origin_world - gravity_world) + lever;

    imu::ImuSample s;
    s.t_ns = t;
    s.gyro_rad_s = R_imu_body * omega_body + gyro_bias + gyro_sigma * noise();
    s.accel_m_s2 = R_imu_body * specific_force_body + accel_bias + accel_sigma * noise();
    samples.push_back(s);
    gyro_bias += gyro_walk * noise();
    accel_bias += accel_walk * noise();
  }
  return samples;
}

}  // namespace aavio::sim
