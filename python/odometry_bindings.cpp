// Odometry: LiveOdometry from Python — push numpy arrays of events and IMU samples, get the
// trajectory; run(): a whole sequence through it, as `aavio run` (bit-identical trajectory).
#include <pybind11/stl.h>

#include <mutex>

#include "aavio/config/config_sources.hpp"
#include "aavio/config/scene_measurement.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/pipeline/live_odometry.hpp"
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
  /// `scene`: the depth of the scene, when measured ahead (a sequence read whole).
  PyOdometry(const std::string& calibration, TimeNs start_ns, const std::string& preset,
             const std::vector<std::string>& config_files, const py::object& set, bool real_time,
             double max_lag_s, bool wait_for_imu,
             const std::optional<pipeline::SceneDepth>& scene = {}) {
    const io::LoadedCalibration loaded = Unwrap(io::LoadCalibration(calibration));
    sources_.preset = preset;
    sources_.files = config_files;
    sources_.overrides = OverridesOf(set);
    preset_reason_ = config::ConfigureForRig(loaded.rig, &sources_, scene);
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

  /// A reader's packet, the cameras complete up to `complete_ns` (C++ only: no GIL needed).
  /// Events from `complete_ns` on are left out (no tick before it uses them); IMU samples
  /// past it stay (the last tick's window ends at the first sample after it).
  Status PushPacket(io::SensorPacket& packet, TimeNs complete_ns) {
    auto cut = [complete_ns](std::vector<events::Event>& v) {
      while (!v.empty() && v.back().t_ns >= complete_ns)
        v.pop_back();
    };
    cut(packet.left);
    cut(packet.right);
    AAVIO_RETURN_IF_ERROR(live_->PushImu(packet.imu));
    AAVIO_RETURN_IF_ERROR(live_->PushEvents(events::Camera::kLeft, packet.left, complete_ns));
    return live_->PushEvents(events::Camera::kRight, packet.right, complete_ns);
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
  // As `aavio run`: with no preset named, the scene's first moments help choose one.
  std::optional<pipeline::SceneDepth> scene;
  if (preset.empty()) {
    scene = Unwrap(config::MeasureSceneDepth(
        reader.get(), Unwrap(io::LoadCalibration(description.calibration)).rig, begin, end));
  }
  // A sequence without an IMU stream: the ticks do not wait for one.
  PyOdometry odometry(description.calibration, begin, preset, config_files, set, false, 0.05,
                      description.imu.has_value(), scene);
  // As `aavio run` feeds the odometry: the reader's packets in order.
  Status status = Status::Ok();
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    io::SensorPacket packet;
    for (std::int64_t packets = 1;; ++packets) {
      Expected<bool> more = reader->Next(&packet);
      if (!more) {
        status = more.status();
        break;
      }
      if (!*more || packet.t_begin_ns >= end) break;
      status = odometry.PushPacket(packet, std::min(packet.t_end_ns, end));
      if (!status.ok()) break;
      // Ctrl-C: Python's handler runs here, every 100 packets (0.1 s of data).
      if (packets % 100 == 0) {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          interrupted = true;
          break;
        }
      }
    }
  }
  if (interrupted) throw py::error_already_set();  // KeyboardInterrupt
  Check(status);
  odometry.Finish(end);
  return odometry.trajectory();
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
