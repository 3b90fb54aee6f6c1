#include "aavio/imu/imu_preintegration.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "aavio/common/format.hpp"
#include "aavio/geometry/rotation.hpp"

namespace aavio::imu {

using geometry::ExpSO3;
using geometry::Hat;

Eigen::Matrix3d Preintegrated::DeltaR(const Eigen::Vector3d& bg) const {
  return delta_R * ExpSO3(dR_dbg * (bg - gyro_bias));
}

Eigen::Vector3d Preintegrated::DeltaV(const Eigen::Vector3d& bg, const Eigen::Vector3d& ba) const {
  return delta_v + dv_dbg * (bg - gyro_bias) + dv_dba * (ba - accel_bias);
}

Eigen::Vector3d Preintegrated::DeltaP(const Eigen::Vector3d& bg, const Eigen::Vector3d& ba) const {
  return delta_p + dp_dbg * (bg - gyro_bias) + dp_dba * (ba - accel_bias);
}

namespace {

// One step of the readings `w` (bias removed) and `acc` over dt seconds: the noise, the bias
// Jacobians and the terms.
void Integrate(const Eigen::Vector3d& w, const Eigen::Vector3d& acc, double dt, double gyro_var,
               double accel_var, Preintegrated* p) {
  const Eigen::Matrix3d dR_step = ExpSO3(w * dt);
  const Eigen::Matrix3d Jr = geometry::RightJacobianSO3(w * dt);
  const Eigen::Matrix3d R = p->delta_R;
  const Eigen::Matrix3d R_acc_hat = R * Hat(acc);

  // Noise: (δφ, δv, δp)_{k+1} = A (δφ, δv, δp)_k + B_g n_g + B_a n_a (Forster eq. 62), with
  // white-noise densities σ: the discrete covariance of each reading is σ²/dt.
  Eigen::Matrix<double, 9, 9> A = Eigen::Matrix<double, 9, 9>::Identity();
  A.block<3, 3>(0, 0) = dR_step.transpose();
  A.block<3, 3>(3, 0) = -R_acc_hat * dt;
  A.block<3, 3>(6, 0) = -0.5 * R_acc_hat * dt * dt;
  A.block<3, 3>(6, 3) = Eigen::Matrix3d::Identity() * dt;
  Eigen::Matrix<double, 9, 3> Bg = Eigen::Matrix<double, 9, 3>::Zero();
  Eigen::Matrix<double, 9, 3> Ba = Eigen::Matrix<double, 9, 3>::Zero();
  Bg.block<3, 3>(0, 0) = Jr * dt;
  Ba.block<3, 3>(3, 0) = R * dt;
  Ba.block<3, 3>(6, 0) = 0.5 * R * dt * dt;
  p->covariance = A * p->covariance * A.transpose() + (gyro_var / dt) * Bg * Bg.transpose() +
                  (accel_var / dt) * Ba * Ba.transpose();

  // Bias Jacobians (Forster appendix B), position and velocity before rotation.
  p->dp_dba += p->dv_dba * dt - 0.5 * R * dt * dt;
  p->dp_dbg += p->dv_dbg * dt - 0.5 * R_acc_hat * p->dR_dbg * dt * dt;
  p->dv_dba -= R * dt;
  p->dv_dbg -= R_acc_hat * p->dR_dbg * dt;
  p->dR_dbg = dR_step.transpose() * p->dR_dbg - Jr * dt;

  // The terms, the acceleration turned by the rotation at the interval's middle (second
  // order: Forster's R_k leaves ½ ω × a dt per step, 0.08 m/s a second in a 3 rad/s turn
  // at 200 Hz).
  const Eigen::Vector3d acc_mid = R * ExpSO3(0.5 * w * dt) * acc;
  p->delta_p += p->delta_v * dt + 0.5 * acc_mid * dt * dt;
  p->delta_v += acc_mid * dt;
  p->delta_R = R * dR_step;
}

}  // namespace

Expected<Preintegrated> Preintegrate(std::span<const ImuSample> samples, TimeNs t_begin_ns,
                                     TimeNs t_end_ns, const Eigen::Vector3d& gyro_bias,
                                     const Eigen::Vector3d& accel_bias, const ImuNoise& noise) {
  if (t_end_ns < t_begin_ns)
    return InvalidArgument("pre-integration interval ends before it begins");
  if (samples.empty() || samples.front().t_ns > t_begin_ns || samples.back().t_ns < t_end_ns) {
    return OutOfRange(StrFormat("the IMU samples do not cover [%s, %s] s",
                                FormatSecondsNs(t_begin_ns).c_str(),
                                FormatSecondsNs(t_end_ns).c_str()));
  }
  Preintegrated p;
  p.t_begin_ns = t_begin_ns;
  p.t_end_ns = t_end_ns;
  p.dt_s = NsToSeconds(t_end_ns - t_begin_ns);
  p.gyro_bias = gyro_bias;
  p.accel_bias = accel_bias;
  const double gyro_var = noise.gyro_noise_density * noise.gyro_noise_density;
  const double accel_var = noise.accel_noise_density * noise.accel_noise_density;
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const ImuSample& a = samples[k];
    const ImuSample& b = samples[k + 1];
    const TimeNs lo = std::max(a.t_ns, t_begin_ns), hi = std::min(b.t_ns, t_end_ns);
    if (hi <= lo) continue;
    if (b.t_ns - a.t_ns > kMaxSampleGapNs) {
      return OutOfRange(StrFormat("the IMU has a gap of %.1f ms at %s s", (b.t_ns - a.t_ns) / 1e6,
                                  FormatSecondsNs(a.t_ns).c_str()));
    }
    const double span = static_cast<double>(b.t_ns - a.t_ns);
    auto weight = [&](TimeNs t) {
      return span > 0.0 ? static_cast<double>(t - a.t_ns) / span : 0.0;
    };
    // Mid-point readings of the clipped interval, bias removed.
    const double s = 0.5 * (weight(lo) + weight(hi));
    const Eigen::Vector3d w = (1.0 - s) * a.gyro_rad_s + s * b.gyro_rad_s - gyro_bias;
    const Eigen::Vector3d acc = (1.0 - s) * a.accel_m_s2 + s * b.accel_m_s2 - accel_bias;
    const double dt = NsToSeconds(hi - lo);
    Integrate(w, acc, dt, gyro_var, accel_var, &p);
  }
  p.delta_R = Eigen::Quaterniond(p.delta_R).normalized().toRotationMatrix();
  return p;
}

}  // namespace aavio::imu
