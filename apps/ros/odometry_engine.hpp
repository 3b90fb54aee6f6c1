#pragma once
// The node's bridge to the library. ROS1's generated message headers do not compile as C++20
// (they use std::allocator<void>::rebind) and aavio's headers need C++20, so the node is two
// halves that meet here, in plain C++17 types: odometry_engine.cpp (C++20) holds the library's
// LiveOdometry and configuration; aavio_ros_node.cpp (C++17) the topics and messages.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace aavio::ros_node {

struct EngineOptions {
  std::string calib_dir;               ///< ESVO folder (left.yaml + right.yaml) or cam_to_cam.yaml
  std::string preset;                  ///< empty: the rig suggests one
  std::string config_file;             ///< a YAML file of parameters, applied after the preset
  std::vector<std::string> overrides;  ///< key=value
  bool real_time = true;
  double max_lag_s = 0.05;
  bool use_imu = true;
};

struct ImuReading {
  std::int64_t t_ns = 0;
  std::array<double, 3> gyro_rad_s{}, accel_m_s2{};
};

/// What a tick produced, in plain types.
struct TickOutput {
  std::int64_t t_ns = 0;
  std::array<double, 3> position{};    ///< rectified left camera in the world [m]
  std::array<double, 4> quaternion{};  ///< x y z w
  /// The camera's velocity in its own frame (m/s, rad/s), from the last 150 ms of poses
  /// (geometry::NewestVelocity); zero until there are two poses.
  std::array<double, 3> linear_mps{}, angular_radps{};
  bool tracked = false;
  // A new local map on this tick (else empty):
  bool has_map = false;
  bool map_confirmed = false;
  std::int64_t map_t_ns = 0;
  std::vector<float> map_points_world;  ///< x y z, x y z, ...
  std::vector<float> map_depth_m;       ///< width × height, row-major, NaN without a point
};

class OdometryEngine {
 public:
  /// Loads the calibration and resolves the configuration; false with `error` set if either fails.
  static std::unique_ptr<OdometryEngine> Create(const EngineOptions& options, std::string* error);
  virtual ~OdometryEngine() = default;

  virtual int width() const = 0;
  virtual int height() const = 0;
  /// The rig, the preset and why, for the log.
  virtual std::string Describe() const = 0;
  /// Warnings about the calibration (e.g. what was assumed), for the log.
  virtual std::vector<std::string> warnings() const = 0;

  /// A serialized EventArray (dvs_msgs, dv_ros_msgs or prophesee_event_msgs) of one camera
  /// (0 left, 1 right). The odometry starts with the first one. False with `error` on bad input.
  virtual bool PushEventArray(int camera, const std::string& type, const std::string& md5,
                              const std::uint8_t* data, std::size_t size, const std::string& topic,
                              std::string* error) = 0;
  virtual bool PushImu(const ImuReading& reading, std::string* error) = 0;
  /// End of input; a summary for the log.
  virtual std::string Finish() = 0;

  /// Every tick, on the processing thread.
  std::function<void(const TickOutput&)> on_tick;
};

}  // namespace aavio::ros_node
