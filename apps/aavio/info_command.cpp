// `aavio info PATH`: what a calibration, an event file or a sequence holds.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/geometry/calibration_difference.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/recording/run_evaluation.hpp"
#include "cli.hpp"
#include "info.hpp"

namespace aavio::cli {

namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
  bool stats = false;
  std::string against;  ///< another calibration of the rig, to compare with
};

double Degrees(const Eigen::Matrix3d& R) {
  return geometry::LogSO3(R).norm() * 180.0 / M_PI;
}

nlohmann::json CameraJson(const geometry::CameraModel& camera) {
  const geometry::CameraIntrinsics& in = camera.intrinsics();
  return {{"width", in.width},
          {"height", in.height},
          {"fx", in.fx},
          {"fy", in.fy},
          {"cx", in.cx},
          {"cy", in.cy},
          {"distortion_model", geometry::DistortionModelName(in.model)},
          {"distortion_coeffs", in.coeffs}};
}

std::string CameraLine(const geometry::CameraModel& camera) {
  const geometry::CameraIntrinsics& in = camera.intrinsics();
  std::string line = StrFormat("fx %.3f  fy %.3f  cx %.3f", in.fx, in.fy, in.cx) +
                     StrFormat("  cy %.3f", in.cy) + "  " +
                     geometry::DistortionModelName(in.model) + " [";
  for (std::size_t i = 0; i < in.coeffs.size(); ++i)
    line += (i ? " " : "") + StrFormat("%.6g", in.coeffs[i]);
  return line + "]";
}

double ValidShare(const cv::Mat& mask) {
  return static_cast<double>(cv::countNonZero(mask)) / static_cast<double>(mask.total());
}

int RunInfoOnData(const InfoOptions& options, Context& ctx) {
  nlohmann::json j;
  std::string text;
  Status status = DescribeData(options.path, options.stats, &j, &text);
  if (!status.ok()) {
    ctx.err << "aavio info: error: " << status.message() << "\n";
    return kExitError;
  }
  if (options.json) {
    ctx.out << j.dump(2) << "\n";
  } else {
    ctx.out << text;
  }
  return kExitOk;
}

int RunInfo(const InfoOptions& options, Context& ctx) {
  if (LooksLikeData(options.path)) {
    if (!options.against.empty()) {
      ctx.err << "aavio info: error: --against compares two calibrations; " << options.path
              << " is data, not a calibration\n";
      return kExitUsage;
    }
    return RunInfoOnData(options, ctx);
  }
  if (options.stats) {
    ctx.err << "aavio info: error: --stats describes event data (.h5, .bag, .txt, .raw or a "
               "sequence); "
            << options.path << " is not\n";
    return kExitUsage;
  }
  Expected<io::LoadedCalibration> loaded = io::LoadCalibration(options.path);
  if (!loaded) {
    ctx.err << "aavio info: error: " << loaded.status().message() << "\n";
    return kExitError;
  }
  const geometry::StereoRig& rig = loaded->rig;
  // --against: how far this calibration is from the other, in what stereo sees.
  std::optional<geometry::CalibrationDifference> difference;
  if (!options.against.empty()) {
    Expected<io::LoadedCalibration> other = io::LoadCalibration(options.against);
    Expected<geometry::CalibrationDifference> d =
        other ? geometry::CompareCalibrations(rig, other->rig)
              : Expected<geometry::CalibrationDifference>(other.status());
    if (!d) {
      ctx.err << "aavio info: error: --against " << options.against << ": " << d.status().message()
              << "\n";
      return kExitError;
    }
    difference = *d;
  }
  const geometry::StereoRectification rect = geometry::BuildStereoRectification(rig);
  const double valid_left = ValidShare(rect.left.valid_mask);
  const double valid_right = ValidShare(rect.right.valid_mask);
  const geometry::RigidTransform& T_rl = rig.T_right_left();

  if (options.json) {
    nlohmann::json j;
    j["path"] = options.path;
    j["kind"] = "calibration";
    j["format"] = loaded->format;
    j["files"] = loaded->files;
    j["left"] = CameraJson(rig.left());
    j["right"] = CameraJson(rig.right());
    j["rectified"] = {{"focal_px", rig.focal_px()},      {"cx_left", rig.cx_left()},
                      {"cx_right", rig.cx_right()},      {"cy", rig.cy()},
                      {"baseline_m", rig.baseline_m()},  {"valid_share_left", valid_left},
                      {"valid_share_right", valid_right}};
    j["T_right_left"] = {{"rotation_deg", Degrees(T_rl.R)},
                         {"translation_m", {T_rl.t.x(), T_rl.t.y(), T_rl.t.z()}}};
    if (rig.T_imu_left()) {
      const geometry::RigidTransform& T = *rig.T_imu_left();
      j["T_imu_left"] = {{"rotation_deg", Degrees(T.R)},
                         {"translation_m", {T.t.x(), T.t.y(), T.t.z()}}};
    } else {
      j["T_imu_left"] = nullptr;
    }
    j["warnings"] = loaded->warnings;
    if (difference) {
      j["against"] = {{"path", options.against},
                      {"difference", recording::CalibrationDifferenceJson(*difference)}};
    }
    ctx.out << j.dump(2) << "\n";
    return kExitOk;
  }

  std::ostream& out = ctx.out;
  out << "calibration  " << options.path << "  (" << loaded->format << ": ";
  for (std::size_t i = 0; i < loaded->files.size(); ++i)
    out << (i ? ", " : "") << loaded->files[i];
  out << ")\n";
  out << "  resolution       " << rig.width() << " x " << rig.height() << " px, both cameras\n";
  out << "  left  (raw)      " << CameraLine(rig.left()) << "\n";
  out << "  right (raw)      " << CameraLine(rig.right()) << "\n";
  out << "  rectified        f "
      << StrFormat("%.3f px, principal point (%.3f, %.3f)", rig.focal_px(), rig.cx_left(),
                   rig.cy());
  if (rig.cx_right() != rig.cx_left()) out << StrFormat(", right cx %.3f", rig.cx_right());
  out << "\n";
  out << "  baseline         "
      << StrFormat("%.4f m   (f*b = %.2f px*m)", rig.baseline_m(),
                   rig.focal_px() * rig.baseline_m())
      << "\n";
  out << "  disparity        "
      << StrFormat("%.1f px at 1 m, %.1f px at 5 m, %.2f px at 50 m", rig.DisparityAtDepth(1.0),
                   rig.DisparityAtDepth(5.0), rig.DisparityAtDepth(50.0))
      << "\n";
  out << "  T_right_left     "
      << StrFormat("rotation %.3f deg, translation (%.4f, %.4f,", Degrees(T_rl.R), T_rl.t.x(),
                   T_rl.t.y())
      << StrFormat(" %.4f) m", T_rl.t.z()) << "\n";
  if (rig.T_imu_left()) {
    const geometry::RigidTransform& T = *rig.T_imu_left();
    out << "  T_imu_left       "
        << StrFormat("rotation %.3f deg, translation (%.4f, %.4f,", Degrees(T.R), T.t.x(), T.t.y())
        << StrFormat(" %.4f) m", T.t.z()) << "\n";
  } else {
    out << "  T_imu_left       none (no IMU extrinsic in this calibration)\n";
  }
  out << "  valid rectified  "
      << StrFormat("%.1f %% of the left image, %.1f %% of the right", 100.0 * valid_left,
                   100.0 * valid_right)
      << "\n";
  if (difference) {
    out << recording::CalibrationDifferenceLine(*difference, rig.focal_px() * rig.baseline_m(),
                                                "  against " + options.against);
  }
  for (const std::string& warning : loaded->warnings)
    out << "warning: " << warning << "\n";
  return kExitOk;
}

}  // namespace

void RegisterInfo(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand(
      "info",
      "Describe a calibration (a folder with left.yaml + right.yaml, either file, or a DSEC "
      "cam_to_cam.yaml), an event file (.h5, .txt, Prophesee .raw, iniVation .aedat4), a ROS1 or "
      "ROS 2 bag (.bag, .db3, .mcap) or a sequence");
  sub->add_option("path", options->path, "File or folder to describe")->required();
  sub->add_flag("--json", options->json, "Print JSON for scripts");
  sub->add_option("--against", options->against,
                  "Another calibration of the same rig: how far PATH is from it in what stereo "
                  "sees (disparity at infinity, rows, f*b)");
  sub->add_flag("--stats", options->stats,
                "Sensor statistics of the events: rate, ON/OFF ratio, isolated (noise-like) "
                "events, same-pixel intervals, hot pixels, events per edge passage");
  sub->callback(
      [&ctx, options] { ctx.action = [&ctx, options] { return RunInfo(*options, ctx); }; });
}

}  // namespace aavio::cli
