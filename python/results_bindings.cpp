// Trajectory (numpy views of times and poses), read_trajectory, evaluate (ATE/RPE as
// `aavio eval --json`), load_run (a run folder's outputs) and simulate.
#include <pybind11/stl.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "aavio/eval/alignment.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/ply.hpp"
#include "aavio/recording/run_evaluation.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "aavio/sim/simulator.hpp"
#include "bindings.hpp"

namespace aavio::python {

Trajectory TrajectoryOf(const py::object& trajectory_or_path) {
  if (py::isinstance<Trajectory>(trajectory_or_path)) return trajectory_or_path.cast<Trajectory>();
  if (!py::isinstance<py::str>(trajectory_or_path) &&
      !py::isinstance(trajectory_or_path, py::module_::import("os").attr("PathLike"))) {
    throw py::type_error("expected a Trajectory or the path of a TUM trajectory file, got " +
                         py::repr(trajectory_or_path).cast<std::string>());
  }
  const std::string path = py::str(trajectory_or_path);
  return {Unwrap(io::ReadTumTrajectory(path)), {}};
}

namespace {

py::array_t<std::int64_t> Times(const Trajectory& t) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(t.poses.size()));
  for (std::size_t i = 0; i < t.poses.size(); ++i)
    a.mutable_data()[i] = t.poses[i].t_ns;
  return a;
}

py::array_t<double> Positions(const Trajectory& t) {
  py::array_t<double> a({static_cast<py::ssize_t>(t.poses.size()), py::ssize_t{3}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < t.poses.size(); ++i)
    for (int k = 0; k < 3; ++k)
      r(static_cast<py::ssize_t>(i), k) = t.poses[i].T_world_body.t[k];
  return a;
}

py::array_t<double> Quaternions(const Trajectory& t) {
  py::array_t<double> a({static_cast<py::ssize_t>(t.poses.size()), py::ssize_t{4}});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < t.poses.size(); ++i) {
    const Eigen::Quaterniond q = t.poses[i].T_world_body.Quaternion();
    const auto row = static_cast<py::ssize_t>(i);
    r(row, 0) = q.x(), r(row, 1) = q.y(), r(row, 2) = q.z(), r(row, 3) = q.w();
  }
  return a;
}

py::object Json(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

py::dict Evaluate(const py::object& estimate, const py::object& ground_truth,
                  const std::string& align, double max_dt_s) {
  recording::TrajectoryEvalOptions options;
  options.alignment = Unwrap(eval::ParseAlignment(align));
  if (!(max_dt_s > 0.0)) throw py::value_error("max_dt_s must be > 0");
  options.max_dt_s = max_dt_s;
  const Trajectory est = TrajectoryOf(estimate), gt = TrajectoryOf(ground_truth);
  const recording::TrajectoryEvaluation e =
      Unwrap(recording::EvaluateTrajectories(est.poses, gt.poses, options));
  return Json(recording::TrajectoryEvaluationJson(e));
}

std::string ReadText(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return "";
  return Unwrap(io::ReadBoundedFile(path.string(), io::kMaxSettingsFileBytes, "run file"));
}

py::dict LoadRun(const std::string& folder) {
  namespace fs = std::filesystem;
  const fs::path dir(folder);
  const fs::path summary = dir / recording::run_files::kSummary;
  if (!fs::exists(summary)) {
    Raise(NotFound(folder + ": no summary.json; is it the --out folder of `aavio run`?"));
  }
  py::dict run;
  run["summary"] = py::module_::import("json").attr("loads")(ReadText(summary));
  run["config"] = ReadText(dir / recording::run_files::kConfig);
  const fs::path trajectory = dir / recording::run_files::kTrajectory;
  run["trajectory"] =
      fs::exists(trajectory)
          ? py::cast(Trajectory{Unwrap(io::ReadTumTrajectory(trajectory.string())), {}})
          : py::none();
  const fs::path ply = dir / recording::run_files::kCloud;
  if (fs::exists(ply)) {
    const recording::ColouredCloud cloud = Unwrap(recording::ReadPly(ply.string()));
    py::array_t<float> points({static_cast<py::ssize_t>(cloud.points.size()), py::ssize_t{3}});
    py::array_t<std::uint8_t> colours(
        {static_cast<py::ssize_t>(cloud.points.size()), py::ssize_t{3}});
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        points.mutable_at(static_cast<py::ssize_t>(i), k) = cloud.points[i][k];
        colours.mutable_at(static_cast<py::ssize_t>(i), k) =
            cloud.colours[i][static_cast<std::size_t>(k)];
      }
    }
    run["map_points"] = points;
    run["map_colours"] = colours;
  } else {
    run["map_points"] = py::none();
    run["map_colours"] = py::none();
  }
  run["depth_dir"] = fs::exists(dir / recording::run_files::kDepthDir)
                         ? py::object(py::str((dir / recording::run_files::kDepthDir).string()))
                         : py::none();
  return run;
}

std::string SimulateSequence(const std::string& out, const std::string& preset, std::uint64_t seed,
                             std::optional<double> duration_s, const std::string& trajectory,
                             double start_s, const std::string& sensor, bool overwrite) {
  sim::SimulationRequest request;
  request.out_dir = out;
  request.overwrite = overwrite;
  request.preset = preset;
  request.seed = seed;
  request.duration_s = duration_s;
  request.trajectory = trajectory;
  request.start_s = start_s;
  request.sensor = sensor;
  Expected<sim::SimulationReport> report = Status::Ok();
  {
    py::gil_scoped_release release;
    report = sim::Simulate(request);
  }
  return Unwrap(std::move(report)).sequence_yaml;
}

}  // namespace

void BindResults(py::module_& m) {
  py::class_<Trajectory>(m, "Trajectory",
                         "Timed poses of the rectified left camera in the world (TUM order: "
                         "quaternion x y z w).")
      .def_property_readonly("t_ns", &Times)
      .def_property_readonly("t_s",
                             [](const Trajectory& t) {
                               py::array_t<double> a(static_cast<py::ssize_t>(t.poses.size()));
                               for (std::size_t i = 0; i < t.poses.size(); ++i)
                                 a.mutable_data()[i] = NsToSeconds(t.poses[i].t_ns);
                               return a;
                             })
      .def_property_readonly("position", &Positions, "(N, 3) metres")
      .def_property_readonly("quaternion", &Quaternions, "(N, 4) x y z w")
      .def_readonly("status", &Trajectory::status,
                    "per pose: 'ok', 'lost', 'no_map' or 'imu' (carried on the IMU alone; empty "
                    "when read from a file)")
      .def("__len__", [](const Trajectory& t) { return t.poses.size(); })
      .def(
          "write",
          [](const Trajectory& t, const std::string& path) {
            Check(io::WriteTumTrajectory(path, t.poses));
          },
          py::arg("path"), "Writes a TUM text file.");

  m.def(
      "read_trajectory", [](const std::string& path) { return TrajectoryOf(py::str(path)); },
      py::arg("path"), "A TUM text trajectory (t x y z qx qy qz qw).");
  m.def("evaluate", &Evaluate, py::arg("estimate"), py::arg("ground_truth"),
        py::arg("align") = "se3", py::arg("max_dt_s") = 0.02,
        "ATE and RPE of an estimate against ground truth (Trajectory objects or TUM files), "
        "as `aavio eval --json`; align: se3, sim3, posyaw or none.");
  m.def("load_run", &LoadRun, py::arg("folder"),
        "A run folder of `aavio run`: summary (dict), config (YAML text), trajectory, "
        "map_points (N, 3) and map_colours, depth_dir.");
  m.def("simulate", &SimulateSequence, py::arg("out"), py::arg("preset") = "mini",
        py::arg("seed") = 1, py::arg("duration_s") = py::none(), py::arg("trajectory") = "",
        py::arg("start_s") = 0.0, py::arg("sensor") = "typical", py::arg("overwrite") = false,
        "Simulates a sequence (as `aavio simulate`) into out; returns its sequence.yaml. "
        "trajectory: a TUM file to follow (a twin of a recording); overwrite: replace a "
        "sequence already in out (else that is an error).");
}

}  // namespace aavio::python
