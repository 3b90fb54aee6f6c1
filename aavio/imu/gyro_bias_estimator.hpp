#pragma once
/// The gyroscope bias used by the prior (docs/tracking.md), in one of three modes:
///   fixed        — the configured value, never changed (the paper);
///   static_init  — the mean reading over the first `static_init_s` of data, accepted only if the
///                  readings were still (every axis' standard deviation below
///                  `static_max_std_rad_s`); otherwise the configured value stays;
///   online       — beyond the paper, as ESVO2 does: over the newest `online_window` consecutive
///                  tracked ticks, the bias that makes the pre-integrated rotation equal the
///                  tracked one, argmin_b |Log(ΔR_pre(b)ᵀ ΔR_tracked)|² (Gauss–Newton, Jacobian by
///                  re-integration); windows do not overlap, and their estimates are averaged
///                  (running mean, then exponentially with `online_gain`). Over a window, the
///                  tracking error enters once, not per tick (tracked rotations telescope); an
///                  estimate implying more than `online_max_rate_rad_s` of change is rejected as a
///                  tracking failure.
/// All rotations here are of the IMU frame.

#include <Eigen/Core>
#include <deque>
#include <limits>
#include <span>

#include "aavio/imu/imu_config.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

class GyroBiasEstimator {
 public:
  GyroBiasEstimator(const ImuConfig& config, TimeNs start_ns);

  const Eigen::Vector3d& bias() const { return bias_; }
  /// True once static_init has decided (either way) or in the other modes.
  bool static_init_done() const { return static_done_; }
  bool static_init_accepted() const { return static_accepted_; }

  /// IMU samples as they arrive (time-ordered; repeats of samples already seen are skipped).
  void AddSamples(std::span<const ImuSample> samples);
  /// A tracked tick [t_begin, t_end]: the IMU samples covering it and the tracked rotation of
  /// the IMU frame. `consecutive` = the previous tick was tracked too (else the window restarts).
  void AddTrackedTick(std::span<const ImuSample> samples, TimeNs t_begin, TimeNs t_end,
                      const Eigen::Matrix3d& delta_R_tracked, bool consecutive);

 private:
  void DecideStatic();

  ImuConfig config_;
  TimeNs static_end_ns_;
  Eigen::Vector3d bias_;
  bool static_done_ = true, static_accepted_ = false;
  TimeNs last_sample_ns_ = std::numeric_limits<TimeNs>::min();
  std::vector<Eigen::Vector3d> static_readings_;
  struct Tick {
    std::vector<ImuSample> samples;
    TimeNs t_begin, t_end;
    Eigen::Matrix3d delta_R_tracked;
  };
  int online_estimates_ = 0;
  std::deque<Tick> window_;  // consecutive tracked ticks, newest last
  void EstimateOnline();
};

}  // namespace aavio::imu
