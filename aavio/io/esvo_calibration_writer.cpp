// Writing ESVO/ESVO2 left.yaml + right.yaml (docs/io.md), full precision.
#include <filesystem>

#include "aavio/common/format.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/config_yaml.hpp"

namespace aavio::io {

namespace {

std::string Matrix(const char* name, const Eigen::MatrixXd& M) {
  std::string text = StrFormat("%s:\n  rows: %d\n  cols: %d\n  data: [", name,
                               static_cast<int>(M.rows()), static_cast<int>(M.cols()));
  for (int r = 0; r < M.rows(); ++r) {
    for (int c = 0; c < M.cols(); ++c) {
      text += StrFormat("%s%.17g", (r == 0 && c == 0) ? "" : ", ", M(r, c));
    }
  }
  return text + "]\n";
}

std::string CameraYaml(const geometry::CameraModel& camera, const Eigen::Matrix3d& R_rect,
                       const geometry::ProjectionMatrix& P, const geometry::StereoRig& rig,
                       const std::string& name) {
  const geometry::CameraIntrinsics& in = camera.intrinsics();
  Eigen::Matrix3d K;
  K << in.fx, 0, in.cx, 0, in.fy, in.cy, 0, 0, 1;
  std::vector<double> coeffs = in.coeffs;
  if (in.model == geometry::DistortionModel::kRadtan && coeffs.size() == 5 && coeffs[4] == 0.0) {
    coeffs.resize(4);  // the 4-coefficient plumb_bob the ESVO family reads
  }
  if (in.model == geometry::DistortionModel::kNone) coeffs = {0.0, 0.0, 0.0, 0.0};
  Eigen::MatrixXd D(1, static_cast<int>(coeffs.size()));
  for (std::size_t i = 0; i < coeffs.size(); ++i)
    D(0, static_cast<int>(i)) = coeffs[i];
  std::string text = StrFormat("image_width: %d\nimage_height: %d\ncamera_name: %s\n", in.width,
                               in.height, name.c_str());
  text += Matrix("camera_matrix", K);
  text += std::string("distortion_model: ") +
          (in.model == geometry::DistortionModel::kEquidistant ? "equidistant" : "plumb_bob") +
          "\n";
  text += Matrix("distortion_coefficients", D);
  text += Matrix("rectification_matrix", R_rect);
  text += Matrix("projection_matrix", P);
  text += Matrix("T_right_left", rig.T_right_left().Matrix().topRows<3>());
  if (rig.T_imu_left()) text += Matrix("T_b_c", rig.T_imu_left()->Matrix().topRows<3>());
  return text;
}

}  // namespace

Status WriteEsvoCalibration(const std::string& folder, const geometry::StereoRig& rig,
                            const std::string& camera_name) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return IoError(folder + ": cannot create the folder (" + ec.message() + ")");
  AAVIO_RETURN_IF_ERROR(WriteTextFile(
      (std::filesystem::path(folder) / "left.yaml").string(),
      CameraYaml(rig.left(), rig.R_rect_left_left(), rig.P_left(), rig, camera_name + "_left")));
  return WriteTextFile((std::filesystem::path(folder) / "right.yaml").string(),
                       CameraYaml(rig.right(), rig.R_rect_right_right(), rig.P_right(), rig,
                                  camera_name + "_right"));
}

}  // namespace aavio::io
