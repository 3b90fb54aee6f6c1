// Odometry: LiveOdometry from Python — push numpy arrays of events and IMU samples, get the
// trajectory; run(): a whole sequence through the library's loop, as `aavio run` (the same
// trajectory).
#include <pybind11/stl.h>

#include <mutex>

#include "aavio/config/config_sources.hpp"
#include "aavio/config/scene_measurement.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/pipeline/live_odometry.hpp"
#include "aavio/pipeline/sequence_run.hpp"
#include "bindings.hpp"

namespace aavio::python {
namespace {

/// "key=value" overrides from a dict or a list of strings.
std::vector<std::string> OverridesOf(const py::object& set) {
  std::vector<std::string> overrides;
  if (set.is_none()) return overrides;
  if (py::isinstance<py::dict>(set)) {
    for (auto [key, value] : set.cast<py::dict>()) {
      std::string text = py::str(value);
      if (py::isinstance<py::bool_>(value)) text = value.cast<bool>() ? "true" : "false";
      overrides.push_back(py::str(key).cast<std::string>() + "=" + text);
    }
    return overrides;
  }
  const auto wrong = [&](const std::string& what) {
    throw py::type_error(
        "set= takes a dict {'mapping.rate_hz': 10} or a list of 'key=value' "
        "strings, got " +
        what);
  };
  if (!py::isinstance<py::list>(set) && !py::isinstance<py::tuple>(set))
    wrong(py::str(py::type::of(set).attr("__name__")).cast<std::string>());
  for (const py::handle item : set) {
    if (!py::isinstance<py::str>(item)) wrong("an item " + py::repr(item).cast<std::string>());
    overrides.push_back(item.cast<std::string>());
  }
  return overrides;
}

class PyOdometry {
 public:
  PyOdometry(const std::string& calibration, TimeNs start_ns, const std::string& preset,
             const std::vector<std::string>& config_files, const py::object& set, bool real_time,
             double max_lag_s, bool wait_for_imu) {
    const io::LoadedCalibration loaded = Unwrap(io::LoadCalibration(calibration));
    sources_.preset = preset;
    sources_.files = config_files;
    sources_.overrides = OverridesOf(set);
    preset_reason_ = config::ConfigureForRig(loaded.rig, &sources_);
    const pipeline::OdometryConfig config = Unwrap(config::ResolveOdometryConfig(sources_));
    live_ = Unwrap(pipeline::LiveOdometry::Create(
        loaded.rig, config, start_ns,
        {.real_time = real_time, .max_lag_s = max_lag_s, .wait_for_imu = wait_for_imu}));
    live_->on_tick = [this](const pipeline::OdometryTick& tick) {
      std::lock_guard<std::mutex> guard(mutex_);
      trajectory_.poses.push_back({tick.t_ns, tick.T_world_cam});
      trajectory_.status.push_back(tracking::TrackingStatusName(tick.status));
      maps_ += tick.map ? 1 : 0;
    };
  }

  void PushEvents(const std::string& camera,
                  const py::array_t<events::Event, py::array::c_style>& events,
                  std::optional<TimeNs> complete_until_ns) {
    if (camera != "left" && camera != "right") {
      throw py::value_error("camera must be 'left' or 'right', not '" + camera + "'");
    }
    const std::span<const events::Event> view = EventsOf(events);  // `events` outlives the call
    Status status;
    {
      py::gil_scoped_release release;
      status = live_->PushEvents(camera == "left" ? events::Camera::kLeft : events::Camera::kRight,
                                 view, complete_until_ns);
    }
    Check(status);
  }

  void PushImu(const py::array_t<ImuRecord, py::array::c_style>& imu) {
    const std::vector<imu::ImuSample> samples = ImuOf(imu);
    Status status;
    {
      py::gil_scoped_release release;
      status = live_->PushImu(samples);
    }
    Check(status);
  }

  void Finish(std::optional<TimeNs> end_ns) {
    Status status;
    {
      py::gil_scoped_release release;
      status = live_->Finish(end_ns);
    }
    Check(status);
  }

  Trajectory trajectory() const {
    std::lock_guard<std::mutex> guard(mutex_);
    return trajectory_;
  }

  py::dict stats() const {
    const pipeline::LiveStats s = live_->stats();
    py::dict d;
    d["events_pushed"] = py::make_tuple(s.events_pushed[0], s.events_pushed[1]);
    d["events_processed"] = py::make_tuple(s.events_processed[0], s.events_processed[1]);
    d["imu_samples_pushed"] = s.imu_samples_pushed;
    d["ticks"] = s.ticks;
    d["skipped_ticks"] = s.skipped_ticks;
    d["skipped_mapping_cycles"] = s.skipped_mapping_cycles;
    d["max_backlog_s"] = s.max_backlog_s;
    d["latency_median_ms"] = s.latency_median_ms;
    d["latency_p99_ms"] = s.latency_p99_ms;
    d["latency_max_ms"] = s.latency_max_ms;
    std::lock_guard<std::mutex> guard(mutex_);
    d["maps"] = maps_;
    return d;
  }

  const std::string& preset() const { return sources_.preset; }
  const std::string& preset_reason() const { return preset_reason_; }

 private:
  config::ConfigSources sources_;
  std::string preset_reason_;
  std::unique_ptr<pipeline::LiveOdometry> live_;
  mutable std::mutex mutex_;
  Trajectory trajectory_;
  std::int64_t maps_ = 0;
};

Trajectory Run(const std::string& sequence_path, const std::string& calibration,
               const std::string& preset, const std::vector<std::string>& config_files,
               const py::object& set, double start_s, std::optional<double> duration_s) {
  const io::SequenceDescription description =
      Unwrap(io::DescribeSequence(sequence_path, calibration));
  if (description.calibration.empty()) {
    throw py::value_error(sequence_path +
                          ": the sequence names no calibration; pass calibration=PATH");
  }
  if (start_s < 0.0 || (duration_s && *duration_s <= 0.0)) {
    throw py::value_error("start_s must be >= 0 and duration_s > 0");
  }
  std::unique_ptr<io::SequenceReader> reader =
      Unwrap(io::SequenceReader::Open(description, io::SequenceReaderOptions{}));
  const TimeNs begin = reader->start_ns() + SecondsToNs(start_s);
  const TimeNs end = duration_s ? begin + SecondsToNs(*duration_s) : reader->end_ns();
  if (start_s > 0.0) Check(reader->Seek(begin));
  // As `aavio run`: the configuration for the rig (with no preset named, the scene's first
  // moments help choose one), the odometry fed by the library's loop.
  config::ConfigSources sources;
  sources.preset = preset;
  sources.files = config_files;
  sources.overrides = OverridesOf(set);
  const geometry::StereoRig rig = Unwrap(io::LoadCalibration(description.calibration)).rig;
  Unwrap(config::ConfigureForSequence(reader.get(), rig, begin, end, &sources));
  const pipeline::OdometryConfig config = Unwrap(config::ResolveOdometryConfig(sources));
  Trajectory trajectory;
  pipeline::Odometry odometry(rig, config, begin);
  odometry.on_tick = [&trajectory](const pipeline::OdometryTick& tick) {
    trajectory.poses.push_back({tick.t_ns, tick.T_world_cam});
    trajectory.status.push_back(tracking::TrackingStatusName(tick.status));
  };
  pipeline::SequenceRunHooks hooks;
  // Ctrl-C: Python's handler runs here, every 100 packets (0.1 s of data).
  std::int64_t packets = 0;
  hooks.stop = [&packets] {
    if (++packets % 100 != 0) return false;
    py::gil_scoped_acquire acquire;
    return PyErr_CheckSignals() != 0;
  };
  pipeline::SequenceRun run;
  {
    py::gil_scoped_release release;
    run = pipeline::RunOdometry(*reader, begin, end, &odometry, hooks);
  }
  if (run.interrupted) throw py::error_already_set();  // KeyboardInterrupt
  Check(run.stopped_by);
  return trajectory;
}

}  // namespace

void BindOdometry(py::module_& m) {
  py::class_<PyOdometry>(m, "Odometry", R"doc(
The odometry fed from Python: push each camera's events and the IMU samples as numpy arrays
(each stream in time order, in chunks of any size), then read the trajectory.

  odo = aavio.Odometry("calibration/", start_ns)      # configured for the rig, as `aavio run`
  odo.push_imu(imu); odo.push_events("left", l); odo.push_events("right", r)
  odo.finish()
  odo.trajectory                                      # aavio.Trajectory

Reproducible by default: the same data gives `aavio run`'s trajectory bit for bit, however it is
split. real_time=True runs the ticks on a thread of their own and, when more than max_lag_s of
data waits, tracks only the newest due tick (every event is still used; stats says what was
skipped). A rig without an IMU: wait_for_imu=False.)doc")
      .def(py::init<const std::string&, TimeNs, const std::string&, const std::vector<std::string>&,
                    const py::object&, bool, double, bool>(),
           py::arg("calibration"), py::arg("start_ns"), py::arg("preset") = "",
           py::arg("config") = std::vector<std::string>{}, py::arg("set") = py::none(),
           py::arg("real_time") = false, py::arg("max_lag_s") = 0.05,
           py::arg("wait_for_imu") = true)
      .def("push_events", &PyOdometry::PushEvents, py::arg("camera"), py::arg("events"),
           py::arg("complete_until_ns") = py::none(),
           "camera 'left' or 'right'; events an EVENT_DTYPE array; complete_until_ns: the stream "
           "has no more events before this time (default: its last event's)")
      .def("push_imu", &PyOdometry::PushImu, py::arg("imu"))
      .def("finish", &PyOdometry::Finish, py::arg("end_ns") = py::none(),
           "End of input: runs the ticks due up to end_ns (default: just past the newest data).")
      .def_property_readonly("trajectory", &PyOdometry::trajectory)
      .def_property_readonly("stats", &PyOdometry::stats)
      .def_property_readonly("preset", &PyOdometry::preset)
      .def_property_readonly("preset_reason", &PyOdometry::preset_reason);

  m.def("run", &Run, py::arg("sequence"), py::arg("calibration") = "", py::arg("preset") = "",
        py::arg("config") = std::vector<std::string>{}, py::arg("set") = py::none(),
        py::arg("start_s") = 0.0, py::arg("duration_s") = py::none(),
        "The odometry on a sequence (as `aavio run SEQUENCE`, same trajectory); returns an "
        "aavio.Trajectory. set: {'mapping.rate_hz': 20} or ['mapping.rate_hz=20'].");
}

}  // namespace aavio::python
