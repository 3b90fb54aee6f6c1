#pragma once
/// Tracking alone: events and IMU in, an Observation and a tracked pose every tick, against maps
/// the caller provides (e.g. built from ground truth) — tracking measured on its own (issue:
/// "a tracking-only mode against a map built from ground truth"). Driven by data time only.

#include <deque>
#include <functional>
#include <span>

#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/tracking/tracker.hpp"

namespace aavio::pipeline {

class TrackingFrontEnd {
 public:
  TrackingFrontEnd(const geometry::StereoRig& rig, const OdometryConfig& config, TimeNs start_ns,
                   const geometry::RigidTransform& T_world_start);

  /// Events of [.., t_end_ns) and IMU samples (time-ordered); runs every tick due.
  Status Process(std::span<const events::Event> left, std::span<const events::Event> right,
                 std::span<const imu::ImuSample> imu, TimeNs t_end_ns);
  void SetMap(std::shared_ptr<const tracking::TrackingMap> map) { tracker_.SetMap(std::move(map)); }

  /// Called with each tick's observation before it is tracked (to swap maps in), and with each
  /// result.
  std::function<void(const events::Observation&)> before_tick;
  std::function<void(const tracking::TrackingResult&, const events::RepresentationTimings&)>
      on_pose;

  static tracking::Camera CameraOf(const geometry::StereoRig& rig);

 private:
  geometry::StereoRectification rectification_;
  events::RepresentationBuilder builder_;
  tracking::Tracker tracker_;
  std::deque<imu::ImuSample> imu_;
  TimeNs tick_ns_, next_tick_ns_;
};

}  // namespace aavio::pipeline
