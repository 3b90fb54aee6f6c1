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
/// nanoseconds; 12 columns is KITTI.
/// EvSLAM's `t tx ty tz qx qy qz qw vx vy vz` (seconds; 11 columns with a non-integer stamp;
/// kEvslam) also gives the body-frame velocity. KITTI (kKitti, 12 columns: [R|t] row by row) has
/// no stamps: they are given beside it (its times.txt).
enum class TrajectoryFormat { kAuto, kTum, kTumNs, kEuroc, kEvslam, kKitti };
const char* TrajectoryFormatName(TrajectoryFormat format);
Expected<TrajectoryFormat> TrajectoryFormatNamed(const std::string& name);

/// A trajectory file read whole: the layout it had, its poses, and EvSLAM's velocities (one per
/// pose; empty for the other layouts).
struct TrajectoryFile {
  TrajectoryFormat format = TrajectoryFormat::kTum;
  std::vector<geometry::StampedPose> poses;
  std::vector<Eigen::Vector3d> v_body_mps;
};
/// `kitti_stamps`: the stamps of a KITTI file's lines, one per pose; empty: line i at i × 0.1 s
/// (two KITTI files paired line by line); null: a KITTI file is an error that says to give them.
Expected<TrajectoryFile> ReadTrajectoryFile(const std::string& path, TrajectoryFormat format,
                                            const std::vector<TimeNs>* kitti_stamps = nullptr);
Expected<TrajectoryFile> ParseTrajectoryFile(const std::string& text, const std::string& origin,
                                             TrajectoryFormat format,
                                             const std::vector<TimeNs>* kitti_stamps = nullptr);
/// The layout of a trajectory file, told from its data (kAuto's rules).
Expected<TrajectoryFormat> DetectTrajectoryFormat(const std::string& path);

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
