#include "aavio/imu/gravity_direction.hpp"

#include <Eigen/Geometry>

#include "aavio/geometry/velocity.hpp"

namespace aavio::imu {
namespace {

constexpr TimeNs kBucketNs = 20 * kNsPerMs;

}  // namespace

Eigen::Matrix3d GravityDirection::R_up_world() const {
  // The shortest rotation taking down_world to −z.
  return Eigen::Quaterniond::FromTwoVectors(down_world, -Eigen::Vector3d::UnitZ())
      .toRotationMatrix();
}

void GravityDirectionEstimator::Add(const ImuSample& sample) {
  if (!sample.accel_m_s2.allFinite()) return;
  if (buckets_.empty() || sample.t_ns >= buckets_.back().start_ns + kBucketNs ||
      sample.t_ns < buckets_.back().start_ns) {
    buckets_.push_back({0, sample.t_ns, Eigen::Vector3d::Zero(), 0});
  }
  Bucket& b = buckets_.back();
  b.t_sum_ns += sample.t_ns - b.start_ns;
  b.f_sum += sample.accel_m_s2;
  ++b.count;
}

std::optional<GravityDirection> GravityDirectionEstimator::Estimate(
    const std::vector<geometry::StampedPose>& trajectory, const Eigen::Matrix3d& R_imu_cam) const {
  if (trajectory.size() < 2) return std::nullopt;
  geometry::PoseBuffer poses(0);
  for (const geometry::StampedPose& p : trajectory)
    if (!poses.Insert(p.t_ns, p.T_world_body).ok()) return std::nullopt;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t used = 0;
  TimeNs first = 0, last = 0;
  for (const Bucket& b : buckets_) {
    const TimeNs t = b.start_ns + b.t_sum_ns / b.count;
    Expected<geometry::RigidTransform> T_world_cam = poses.Query(t);
    if (!T_world_cam) continue;
    // f in the IMU frame → world: R_world_imu = R_world_cam · R_imu_camᵀ.
    sum += T_world_cam->R * R_imu_cam.transpose() * (b.f_sum / b.count);
    if (used == 0) first = t;
    last = t;
    ++used;
  }
  if (used == 0 || NsToSeconds(last - first) < kMinSpanS) return std::nullopt;
  // mean(R·f) = mean(a) − g, and mean(a) = (v_last − v_first) / span: the trajectory's own
  // velocities at both ends remove what the motion leaves in the mean.
  const std::vector<geometry::StampedVelocity> velocities =
      geometry::EstimateVelocities(trajectory, geometry::kDefaultVelocityHalfWindowNs);
  const geometry::Sampled ends = geometry::SampleAt(trajectory, velocities, {first, last});
  Eigen::Vector3d mean_acceleration = Eigen::Vector3d::Zero();
  if (ends.poses.size() == 2 && ends.velocities[0].valid && ends.velocities[1].valid) {
    const Eigen::Vector3d v_first = ends.poses[0].T_world_body.R * ends.velocities[0].v_body_mps;
    const Eigen::Vector3d v_last = ends.poses[1].T_world_body.R * ends.velocities[1].v_body_mps;
    mean_acceleration = (v_last - v_first) / NsToSeconds(last - first);
  }
  GravityDirection g;
  const Eigen::Vector3d mean = sum / static_cast<double>(used) - mean_acceleration;
  g.magnitude_m_s2 = mean.norm();
  if (!(g.magnitude_m_s2 > 0.0)) return std::nullopt;
  g.down_world = -mean / g.magnitude_m_s2;
  g.samples = used;
  g.span_s = NsToSeconds(last - first);
  return g;
}

}  // namespace aavio::imu
