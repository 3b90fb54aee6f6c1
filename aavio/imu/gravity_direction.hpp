#pragma once
/// Where "down" is in a run's world, from the accelerometer and the tracked orientations: the
/// accelerometer measures f = R_world_imuᵀ·(a − g), so the time mean of R_world_imu·f is
/// mean(a) − g, and mean(a) is the velocity change over the span divided by it, which the
/// trajectory gives (geometry::EstimateVelocities at both ends). Needs no IMU back-end and no
/// rest; what it gives is checked by its magnitude (|g| ≈ 9.81 m/s²). Accelerometer biases tilt
/// it by about |b_a|/g (0.1 m/s²: 0.6°).
/// Used to turn a run's world so that z is up (evaluation's posyaw alignment assumes it).

#include <optional>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

struct GravityDirection {
  Eigen::Vector3d down_world = Eigen::Vector3d::Zero();  ///< unit vector along g in the world
  double magnitude_m_s2 = 0.0;  ///< |mean of R_world_imu·f|: ≈ 9.81 when the estimate holds
  std::size_t samples = 0;      ///< accelerometer buckets used (one per 20 ms)
  double span_s = 0.0;          ///< time they cover
  /// The rotation that takes the world to one with z up (g along −z), turning as little as
  /// possible.
  Eigen::Matrix3d R_up_world() const;
};

/// Accumulates accelerometer readings in 20 ms buckets (bounded memory: 50 a second), then
/// rotates them with the trajectory's orientations.
class GravityDirectionEstimator {
 public:
  void Add(const ImuSample& sample);
  /// From the camera trajectory (T_world_cam) and the IMU ← camera extrinsic: empty when fewer
  /// than kMinSpanS seconds of readings fall within the trajectory.
  std::optional<GravityDirection> Estimate(const std::vector<geometry::StampedPose>& trajectory,
                                           const Eigen::Matrix3d& R_imu_cam) const;
  static constexpr double kMinSpanS = 2.0;

 private:
  struct Bucket {
    TimeNs t_sum_ns = 0;  // of the samples, for their mean stamp (relative to the bucket start)
    TimeNs start_ns = 0;
    Eigen::Vector3d f_sum = Eigen::Vector3d::Zero();
    int count = 0;
  };
  std::vector<Bucket> buckets_;
};

}  // namespace aavio::imu
