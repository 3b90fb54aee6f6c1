#pragma once
/// A C2 trajectory through stamped poses, with analytic derivatives (issue: "a C2 spline through
/// the poses"). Position: a natural cubic spline per axis through the given positions at their
/// own stamps. Rotation: a uniform cumulative cubic B-spline on SO(3) (Kim et al. 1995; the form
/// Basalt and Sommer et al. 2020 use), whose control rotations are solved so that the curve
/// passes through the given orientations at the knots. Both are C2, so velocity, acceleration and
/// angular velocity are continuous — what an IMU needs.
///
/// Frames: the spline gives T_world_body(t); angular velocity is in the body frame, linear
/// velocity and acceleration in the world frame.

#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::sim {

class MotionSpline {
 public:
  /// `poses` sorted by strictly increasing stamps, at least 2. `knot_interval_ns` = rotation
  /// B-spline knot spacing; 0 picks the median spacing of the poses (clamped to [5, 100] ms).
  static Expected<MotionSpline> Fit(const std::vector<geometry::StampedPose>& poses,
                                    TimeNs knot_interval_ns = 0);

  TimeNs t_begin_ns() const { return t_begin_ns_; }
  TimeNs t_end_ns() const { return t_end_ns_; }

  /// Valid for t in [t_begin, t_end]; clamped outside.
  geometry::RigidTransform Pose(TimeNs t_ns) const;
  Eigen::Vector3d Position(TimeNs t_ns) const;
  Eigen::Matrix3d Rotation(TimeNs t_ns) const;
  Eigen::Vector3d LinearVelocity(TimeNs t_ns) const;      ///< world frame [m/s]
  Eigen::Vector3d LinearAcceleration(TimeNs t_ns) const;  ///< world frame [m/s²]
  Eigen::Vector3d AngularVelocity(TimeNs t_ns) const;     ///< body frame [rad/s]

  /// Largest rotation error at the input stamps after fitting [rad] (diagnostic).
  double max_fit_error_rad() const { return max_fit_error_rad_; }

 private:
  struct CubicSegment {  // p(s) = a + b s + c s² + d s³, s in seconds from the segment start
    Eigen::Vector3d a, b, c, d;
  };
  std::size_t Segment(double t_s) const;
  /// Index i and fraction u of the B-spline segment holding t.
  void Knot(double t_s, std::size_t* i, double* u) const;
  Eigen::Matrix3d RotationAt(double t_s, Eigen::Vector3d* omega_body) const;

  TimeNs t_begin_ns_ = 0;
  TimeNs t_end_ns_ = 0;
  std::vector<double> times_s_;           // position knots, seconds from t_begin
  std::vector<CubicSegment> segments_;    // one per interval of times_s_
  double knot_dt_s_ = 0.01;               // rotation B-spline knot spacing
  std::vector<Eigen::Matrix3d> control_;  // rotation control points, knot k at (k − 1) · dt
  double max_fit_error_rad_ = 0.0;
};

}  // namespace aavio::sim
