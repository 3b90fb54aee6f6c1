#pragma once
/// TUM trajectory files (docs/evaluation.md): `timestamp tx ty tz qx qy qz qw` per line, seconds,
/// T_world_body, Hamilton quaternion with w last. The name rpg_trajectory_evaluation expects for
/// estimates is stamped_traj_estimate.txt.

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::io {

/// Reads a TUM file: columns separated by whitespace or commas, `#` comment lines and blank lines
/// skipped, timestamps parsed exactly to nanoseconds, quaternions normalised (their norm must be
/// within 1 % of 1). Stamps must increase strictly. Errors give "file:line: what; fix".
Expected<std::vector<geometry::StampedPose>> ReadTumTrajectory(const std::string& path);
/// The same, from text; `origin` names it in messages.
Expected<std::vector<geometry::StampedPose>> ParseTumTrajectory(const std::string& text,
                                                                const std::string& origin);

/// Trajectory text layouts aavio reads. TUM: `t tx ty tz qx qy qz qw`, t in seconds (kTum) or
/// whole nanoseconds (kTumNs); EuRoC CSV: `t[ns], x, y, z, qw, qx, qy, qz[, ...]` (w first; the
/// state_groundtruth_estimate0 files' velocity and bias columns after it are ignored). kAuto
/// tells them apart from the data: a `[ns]` or `q_RS_w` header line, or 11 and more columns, is
/// EuRoC; integer stamps that are epoch-sized (from 10^12) or step by 1000 and more are
/// nanoseconds. KITTI's 12-column files have no timestamps and are refused by name.
/// EvSLAM's `t tx ty tz qx qy qz qw vx vy vz` (seconds; 11 columns with a non-integer stamp) is
/// read for its poses (kEvslam).
enum class TrajectoryFormat { kAuto, kTum, kTumNs, kEuroc, kEvslam };
const char* TrajectoryFormatName(TrajectoryFormat format);
Expected<TrajectoryFormat> TrajectoryFormatNamed(const std::string& name);

/// Reads a trajectory of `format` (the TUM reader's rules: exact stamps, quaternions within 1 %
/// of unit norm, strictly increasing stamps, "file:line: what; fix" errors).
Expected<std::vector<geometry::StampedPose>> ReadTrajectory(const std::string& path,
                                                            TrajectoryFormat format);
Expected<std::vector<geometry::StampedPose>> ParseTrajectory(const std::string& text,
                                                             const std::string& origin,
                                                             TrajectoryFormat format);

/// Writes (truncating) with a `# timestamp tx ty tz qx qy qz qw` header, 9-decimal seconds and
/// 9-decimal pose values, single spaces.
Status WriteTumTrajectory(const std::string& path, const std::vector<geometry::StampedPose>& poses);
std::string FormatTumTrajectory(const std::vector<geometry::StampedPose>& poses);
/// The header line and one pose's line of that layout, for writing a trajectory as it grows.
inline constexpr char kTumHeader[] = "# timestamp tx ty tz qx qy qz qw\n";
std::string FormatTumPose(const geometry::StampedPose& pose);

}  // namespace aavio::io
