#include "aavio/pipeline/tracking_front_end.hpp"

#include <vector>

namespace aavio::pipeline {

tracking::Camera TrackingFrontEnd::CameraOf(const geometry::StereoRig& rig) {
  return {rig.width(), rig.height(), rig.focal_px(), rig.cx_left(), rig.cy()};
}

TrackingFrontEnd::TrackingFrontEnd(const geometry::StereoRig& rig, const OdometryConfig& config,
                                   TimeNs start_ns, const geometry::RigidTransform& T_world_start)
    : rectification_(geometry::BuildStereoRectification(rig)),
      builder_(rectification_, rig.width(), rig.height(),
               {config.time_surface, config.adaptive_accumulation, config.edge_sampling,
                static_cast<std::uint64_t>(config.pipeline.random_seed)},
               start_ns),
      tracker_(CameraOf(rig), config.tracking, config.imu,
               rig.T_imu_rect_left().value_or(geometry::RigidTransform()).R,
               static_cast<std::uint64_t>(config.pipeline.random_seed)),
      tick_ns_(SecondsToNs(1.0 / config.time_surface.rate_hz)),
      next_tick_ns_(start_ns + tick_ns_) {
  tracker_.Reset(start_ns, T_world_start);
}

Status TrackingFrontEnd::Process(std::span<const events::Event> left,
                                 std::span<const events::Event> right,
                                 std::span<const imu::ImuSample> imu, TimeNs t_end_ns) {
  AAVIO_RETURN_IF_ERROR(builder_.AddEvents(events::Camera::kLeft, left));
  AAVIO_RETURN_IF_ERROR(builder_.AddEvents(events::Camera::kRight, right));
  imu_.insert(imu_.end(), imu.begin(), imu.end());
  while (next_tick_ns_ < t_end_ns) {
    const TimeNs t = next_tick_ns_;
    next_tick_ns_ += tick_ns_;
    events::Observation obs;
    AAVIO_RETURN_IF_ERROR(builder_.Build(t, &obs));
    if (before_tick) before_tick(obs);
    // The IMU samples around (previous tick, t]: keep one before the previous tick.
    while (imu_.size() > 2 && imu_[1].t_ns <= t - tick_ns_)
      imu_.pop_front();
    const std::vector<imu::ImuSample> window(imu_.begin(), imu_.end());
    const tracking::TrackingResult result =
        tracker_.Track(obs, rectification_.left.valid_mask, window);
    if (on_pose) on_pose(result, obs.timings);
  }
  return Status::Ok();
}

}  // namespace aavio::pipeline
