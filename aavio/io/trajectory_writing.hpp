#pragma once
/// Trajectories written in the layouts other tools read (docs/cli.md, `aavio run --format`), with
/// velocities where the layout has them, and the stamps a trajectory is wanted at
/// (`aavio run --poses-at`).

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/velocity.hpp"
#include "aavio/io/trajectory_io.hpp"

namespace aavio::io {

/// Writes io::TrajectoryFormat's layouts (the ones `aavio eval` reads). tum: `t tx ty tz qx qy qz
/// qw` (s; kAuto writes it too); tum_ns: the same with integer nanosecond stamps; kitti: the 3×4
/// matrix [R|t] row by row, no stamps (with `<name>_times.txt` beside it, KITTI's times.txt);
/// euroc: `t[ns],x,y,z,qw,qx,qy,qz,vx,vy,vz` with the velocity in the world frame (as EuRoC's
/// state_groundtruth_estimate0); evslam: `t x y z qx qy qz qw vx vy vz` (s), the velocity in the
/// body (camera) frame.
/// A format a trajectory can be written in, by name (every one but auto).
Expected<TrajectoryFormat> WritableTrajectoryFormat(const std::string& name);
/// The file name `aavio run` gives it: trajectory_tum.txt, trajectory_kitti.txt, …
std::string TrajectoryFileName(TrajectoryFormat format);

/// `velocities`: one per pose (geometry::EstimateVelocities), or empty for the layouts without.
std::string FormatTrajectory(const std::vector<geometry::StampedPose>& poses,
                             const std::vector<geometry::StampedVelocity>& velocities,
                             TrajectoryFormat format);
/// Writes it at `path`; KITTI also writes its stamps as `<path without .txt>_times.txt`.
Status WriteTrajectory(const std::string& path, const std::vector<geometry::StampedPose>& poses,
                       const std::vector<geometry::StampedVelocity>& velocities,
                       TrajectoryFormat format);

/// `t vx vy vz wx wy wz` per pose: body-frame linear (m/s) and angular (rad/s) velocity.
std::string FormatVelocities(const std::vector<geometry::StampedVelocity>& velocities);

/// The stamps in the first column of a text file (a reference-time list, or any TUM, EuRoC or
/// EvSLAM trajectory): seconds, or nanoseconds when the values are integers that are epoch-sized
/// or step by 1000 and more (as trajectories are told apart). Must increase strictly.
Expected<std::vector<TimeNs>> ReadStamps(const std::string& path);

}  // namespace aavio::io
