// Conversions the bindings share: Status to Python exceptions, events and IMU samples to and
// from numpy arrays.
#include <cstring>

#include "bindings.hpp"

namespace aavio::python {

void Raise(const Status& status) {
  switch (status.code()) {
    case StatusCode::kInvalidArgument:
    case StatusCode::kOutOfRange:
    case StatusCode::kParseError:
    case StatusCode::kFailedPrecondition:
      throw py::value_error(status.message());
    case StatusCode::kNotFound:
      PyErr_SetString(PyExc_FileNotFoundError, status.message().c_str());
      throw py::error_already_set();
    default:
      throw std::runtime_error(status.message());
  }
}

py::array_t<events::Event> EventArray(const std::vector<events::Event>& events) {
  py::array_t<events::Event> a(static_cast<py::ssize_t>(events.size()));
  if (!events.empty())
    std::memcpy(a.mutable_data(), events.data(), events.size() * sizeof(events[0]));
  return a;
}

py::array_t<ImuRecord> ImuArray(const std::vector<imu::ImuSample>& samples) {
  py::array_t<ImuRecord> a(static_cast<py::ssize_t>(samples.size()));
  ImuRecord* out = a.mutable_data();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    out[i].t_ns = samples[i].t_ns;
    for (int k = 0; k < 3; ++k) {
      out[i].gyro_rad_s[k] = samples[i].gyro_rad_s[k];
      out[i].accel_m_s2[k] = samples[i].accel_m_s2[k];
    }
  }
  return a;
}

std::span<const events::Event> EventsOf(
    const py::array_t<events::Event, py::array::c_style>& a) {
  if (a.ndim() != 1) throw py::value_error("events: expected a 1-D array of aavio.EVENT_DTYPE");
  return {a.data(), static_cast<std::size_t>(a.size())};
}

std::vector<imu::ImuSample> ImuOf(const py::array_t<ImuRecord, py::array::c_style>& a) {
  if (a.ndim() != 1) throw py::value_error("imu: expected a 1-D array of aavio.IMU_DTYPE");
  std::vector<imu::ImuSample> samples(static_cast<std::size_t>(a.size()));
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const ImuRecord& r = a.data()[i];
    samples[i].t_ns = r.t_ns;
    samples[i].gyro_rad_s = Eigen::Vector3d(r.gyro_rad_s[0], r.gyro_rad_s[1], r.gyro_rad_s[2]);
    samples[i].accel_m_s2 = Eigen::Vector3d(r.accel_m_s2[0], r.accel_m_s2[1], r.accel_m_s2[2]);
  }
  return samples;
}

}  // namespace aavio::python
