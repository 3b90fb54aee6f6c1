#pragma once
// The `aavio` Python module (pybind11): shared conversions (conversions.cpp) and one Bind* per
// file; module.cpp defines the module.
//   sequence_bindings.cpp  open_sequence, Sequence, packets; events and IMU as numpy arrays
//   odometry_bindings.cpp  Odometry (LiveOdometry from Python), run
//   results_bindings.cpp   Trajectory, read_trajectory, evaluate, load_run, simulate

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/event.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::python {

namespace py = pybind11;

/// One IMU sample as a numpy record: t_ns, gyro_rad_s[3], accel_m_s2[3].
struct ImuRecord {
  std::int64_t t_ns;
  double gyro_rad_s[3];
  double accel_m_s2[3];
};

/// Raises the Python exception for a failed Status: ValueError (bad arguments or data),
/// FileNotFoundError, or RuntimeError.
[[noreturn]] void Raise(const Status& status);
inline void Check(const Status& status) {
  if (!status.ok()) Raise(status);
}
template <typename T>
T Unwrap(Expected<T> value) {
  if (!value) Raise(value.status());
  return std::move(*value);
}

py::array_t<events::Event> EventArray(const std::vector<events::Event>& events);
py::array_t<ImuRecord> ImuArray(const std::vector<imu::ImuSample>& samples);
/// A 1-D array of the event dtype (C-contiguous), as a span over its memory (valid while the
/// array is).
std::span<const events::Event> EventsOf(const py::array_t<events::Event, py::array::c_style>& a);
std::vector<imu::ImuSample> ImuOf(const py::array_t<ImuRecord, py::array::c_style>& a);

/// A trajectory as Python sees it: times and poses, with a tracking status per pose when it
/// comes from the odometry.
struct Trajectory {
  std::vector<geometry::StampedPose> poses;
  std::vector<std::string> status;
};
/// A Trajectory, or a TUM file's path.
Trajectory TrajectoryOf(const py::object& trajectory_or_path);

void BindSequence(py::module_& m);
void BindOdometry(py::module_& m);
void BindResults(py::module_& m);

}  // namespace aavio::python
