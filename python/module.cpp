// The `aavio` Python module: open sequences and read their events as numpy arrays, run the
// odometry on a sequence or on arrays, evaluate trajectories, load a run's outputs, simulate.
// docs/python.md is the guide.

#include "bindings.hpp"

PYBIND11_MODULE(aavio, m) {
  using namespace aavio::python;
  m.doc() =
      "aavio: IMU-aided event-based stereo visual odometry (Niu, Zhong, Zhou, ICRA 2024).\n"
      "Events are numpy arrays of EVENT_DTYPE (t_ns int64, x, y uint16 raw pixels, polarity\n"
      "uint8), IMU samples of IMU_DTYPE (t_ns, gyro_rad_s[3], accel_m_s2[3]).";
  // Events and IMU samples are numpy arrays: without numpy there is no module, and the error says
  // which Python lacks it and how to install it (else: "initialization failed").
  try {
    py::module_::import("numpy");
  } catch (py::error_already_set& e) {
    const std::string python = py::module_::import("sys").attr("executable").cast<std::string>();
    throw py::import_error("aavio needs numpy, which this Python (" + python + ") cannot import (" +
                           e.what() + "): install it with `" + python +
                           " -m pip install numpy`, or for Debian's /usr/bin/python3 with "
                           "`apt install python3-numpy`");
  }
  PYBIND11_NUMPY_DTYPE(aavio::events::Event, t_ns, x, y, polarity);
  PYBIND11_NUMPY_DTYPE(ImuRecord, t_ns, gyro_rad_s, accel_m_s2);
  m.attr("EVENT_DTYPE") = py::dtype::of<aavio::events::Event>();
  m.attr("IMU_DTYPE") = py::dtype::of<ImuRecord>();
  BindSequence(m);
  BindOdometry(m);
  BindResults(m);
}
