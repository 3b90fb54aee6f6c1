#pragma once
/// What a run's poses give besides the trajectory: the camera's velocity at every pose
/// (stamped_velocity_estimate.txt), the trajectory in the format and at the stamps asked for, and
/// summary.json's "motion" (speeds, turn rate, the measured gravity, the stamps written).

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/imu/gravity_direction.hpp"
#include "aavio/io/trajectory_io.hpp"

namespace aavio::recording {

struct MotionOutputs {
  std::string out_dir;
  /// Also the trajectory in this format (io::TrajectoryFileName), at `poses_at` when not empty;
  /// kTum with no stamps: nothing more.
  io::TrajectoryFormat format = io::TrajectoryFormat::kTum;
  std::vector<TimeNs> poses_at;
};

/// Writes the files of `what` for `trajectory` (in the world the files are in) and returns
/// "motion"; a failed write is added to `failures` and the rest still written. `gravity`: as
/// measured in the first camera's world; `R_out_first`: that world → the files' world.
nlohmann::json WriteMotion(const MotionOutputs& what,
                           const std::vector<geometry::StampedPose>& trajectory,
                           const std::optional<imu::GravityDirection>& gravity,
                           const Eigen::Matrix3d& R_out_first, std::vector<Status>* failures);

}  // namespace aavio::recording
