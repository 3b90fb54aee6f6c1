#pragma once
/// The names of what a run folder holds (written by RunRecorder; read by `aavio eval --run`,
/// `aavio report` and the Python module's load_run).

namespace aavio::recording::run_files {

inline constexpr char kTrajectory[] = "stamped_traj_estimate.txt";
inline constexpr char kTrajectoryPart[] = "stamped_traj_estimate.txt.part";  ///< while it goes
inline constexpr char kVelocity[] = "stamped_velocity_estimate.txt";         ///< one per pose
inline constexpr char kSummary[] = "summary.json";
inline constexpr char kTimings[] = "timings.csv";
inline constexpr char kConfig[] = "config.yaml";
inline constexpr char kCloud[] = "map.ply";
inline constexpr char kCloudPart[] = "map.ply.part";  ///< map.ply's points while the run goes
inline constexpr char kDepthDir[] = "depth";
inline constexpr char kReserve[] = ".aavio_reserve";  ///< space for Finish on a full disk

}  // namespace aavio::recording::run_files
