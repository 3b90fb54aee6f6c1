#include "aavio/imu/gyro_bias_estimator.hpp"

#include <algorithm>
#include <cmath>

#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/gyro_preintegration.hpp"

namespace aavio::imu {

GyroBiasEstimator::GyroBiasEstimator(const ImuConfig& config, TimeNs start_ns)
    : config_(config),
      static_end_ns_(start_ns + SecondsToNs(config.static_init_s)),
      bias_(config.gyro_bias_rad_s[0], config.gyro_bias_rad_s[1], config.gyro_bias_rad_s[2]),
      static_done_(config.bias_mode != GyroBiasMode::kStaticInit) {}

void GyroBiasEstimator::AddSamples(std::span<const ImuSample> samples) {
  if (static_done_) return;
  for (const ImuSample& s : samples) {
    if (s.t_ns <= last_sample_ns_) continue;
    last_sample_ns_ = s.t_ns;
    if (s.t_ns > static_end_ns_) {
      DecideStatic();
      return;
    }
    static_readings_.push_back(s.gyro_rad_s);
  }
}

void GyroBiasEstimator::DecideStatic() {
  static_done_ = true;
  if (static_readings_.size() < 10) return;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& w : static_readings_)
    mean += w;
  mean /= static_cast<double>(static_readings_.size());
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& w : static_readings_)
    var += (w - mean).cwiseAbs2();
  var /= static_cast<double>(static_readings_.size());
  static_accepted_ = var.cwiseSqrt().maxCoeff() < config_.static_max_std_rad_s;
  if (static_accepted_) bias_ = mean;
  static_readings_ = {};
}

void GyroBiasEstimator::AddTrackedTick(std::span<const ImuSample> samples, TimeNs t_begin,
                                       TimeNs t_end, const Eigen::Matrix3d& delta_R_tracked,
                                       bool consecutive) {
  if (config_.bias_mode != GyroBiasMode::kOnline || t_end <= t_begin) return;
  if (!consecutive) window_.clear();
  Tick tick{{}, t_begin, t_end, delta_R_tracked};
  // The samples that bracket [t_begin, t_end], as IntegrateGyro needs.
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i + 1 < samples.size() && samples[i + 1].t_ns <= t_begin) continue;
    tick.samples.push_back(samples[i]);
    if (samples[i].t_ns >= t_end) break;
  }
  window_.push_back(std::move(tick));
  if (static_cast<int>(window_.size()) == config_.online_window) {
    EstimateOnline();
    window_.clear();  // windows do not overlap: their tracking errors are independent
  }
}

void GyroBiasEstimator::EstimateOnline() {
  Eigen::Matrix3d tracked = Eigen::Matrix3d::Identity();
  for (const Tick& t : window_)
    tracked = tracked * t.delta_R_tracked;
  auto residual = [&](const Eigen::Vector3d& b, Eigen::Vector3d* r) {
    Eigen::Matrix3d pre = Eigen::Matrix3d::Identity();
    for (const Tick& t : window_) {
      Expected<Eigen::Matrix3d> d = IntegrateGyro(t.samples, t.t_begin, t.t_end, b);
      if (!d) return false;
      pre = pre * *d;
    }
    *r = geometry::LogSO3(pre.transpose() * tracked);
    return true;
  };
  Eigen::Vector3d b = bias_;
  for (int iteration = 0; iteration < 2; ++iteration) {
    Eigen::Vector3d r0;
    if (!residual(b, &r0)) return;
    Eigen::Matrix3d J;
    constexpr double kStep = 1e-4;  // rad/s
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d bk = b, rk;
      bk[k] += kStep;
      if (!residual(bk, &rk)) return;
      J.col(k) = (rk - r0) / kStep;
    }
    b -= J.colPivHouseholderQr().solve(r0);
  }
  if ((b - bias_).norm() > config_.online_max_rate_rad_s || !b.allFinite()) return;
  // Running mean of the window estimates, then an exponential average with online_gain.
  ++online_estimates_;
  const double gain = std::max(config_.online_gain, 1.0 / online_estimates_);
  bias_ += gain * (b - bias_);
}

}  // namespace aavio::imu
