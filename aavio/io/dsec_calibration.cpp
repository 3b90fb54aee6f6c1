// DSEC cam_to_cam.yaml (docs/io.md).
#include <cmath>
#include <cstdio>

#include "aavio/common/format.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/yaml_reading.hpp"

namespace aavio::io {

namespace {

using geometry::CameraIntrinsics;
using geometry::DistortionModel;

struct DsecCamera {
  CameraIntrinsics intrinsics;
};

Expected<YAML::Node> Path(const YAML::Node& root, std::initializer_list<const char*> keys,
                          const std::string& file) {
  YAML::Node node;
  node.reset(root);  // Node::operator= would assign through the reference (yaml-cpp semantics)
  std::string path;
  for (const char* key : keys) {
    path += (path.empty() ? "" : ".") + std::string(key);
    if (!node.IsMap() || !node[key]) return NotFound(file + ": missing key '" + path + "'");
    node.reset(node[key]);
  }
  return node;
}

/// camera_matrix [fx, fy, cx, cy] (4 numbers, not 3x3) and resolution [width, height].
Expected<CameraIntrinsics> ReadDsecIntrinsics(const YAML::Node& root, const char* cam,
                                              const std::string& file, bool distorted) {
  const std::string prefix = std::string("intrinsics.") + cam;
  CameraIntrinsics in;
  Expected<YAML::Node> k = Path(root, {"intrinsics", cam, "camera_matrix"}, file);
  if (!k) return k.status();
  Expected<std::vector<double>> kv = yaml::ToNumbers(*k, file, prefix + ".camera_matrix");
  if (!kv) return kv.status();
  if (kv->size() != 4) {
    return ParseError(yaml::Where(file, *k) + ": " + prefix +
                      ".camera_matrix must list 4 numbers [fx, fy, cx, cy], got " +
                      std::to_string(kv->size()));
  }
  in.fx = (*kv)[0];
  in.fy = (*kv)[1];
  in.cx = (*kv)[2];
  in.cy = (*kv)[3];
  Expected<YAML::Node> res = Path(root, {"intrinsics", cam, "resolution"}, file);
  if (!res) return res.status();
  Expected<std::vector<double>> rv = yaml::ToNumbers(*res, file, prefix + ".resolution");
  if (!rv) return rv.status();
  if (rv->size() != 2 || (*rv)[0] != std::floor((*rv)[0]) || (*rv)[1] != std::floor((*rv)[1])) {
    return ParseError(yaml::Where(file, *res) + ": " + prefix +
                      ".resolution must be [width, height] in whole pixels");
  }
  in.width = static_cast<int>((*rv)[0]);
  in.height = static_cast<int>((*rv)[1]);
  if (!distorted) return in;

  Expected<YAML::Node> model = Path(root, {"intrinsics", cam, "distortion_model"}, file);
  if (!model) return model.status();
  Expected<std::string> name = yaml::ToString(*model, file, prefix + ".distortion_model");
  if (!name) return name.status();
  if (*name == "radtan" || *name == "plumb_bob") {
    in.model = DistortionModel::kRadtan;
  } else if (*name == "equidistant") {
    in.model = DistortionModel::kEquidistant;
  } else {
    return ParseError(yaml::Where(file, *model) + ": " + prefix + ".distortion_model '" + *name +
                      "' is not supported; use radtan or equidistant");
  }
  Expected<YAML::Node> coeffs = Path(root, {"intrinsics", cam, "distortion_coeffs"}, file);
  if (!coeffs) return coeffs.status();
  Expected<std::vector<double>> cv = yaml::ToNumbers(*coeffs, file, prefix + ".distortion_coeffs");
  if (!cv) return cv.status();
  in.coeffs = *cv;
  return in;
}

Expected<Eigen::MatrixXd> ReadMatrix(const YAML::Node& root,
                                     std::initializer_list<const char*> keys,
                                     const std::string& file, int rows, int cols) {
  Expected<YAML::Node> node = Path(root, keys, file);
  if (!node) return node.status();
  std::string name;
  for (const char* key : keys)
    name += (name.empty() ? "" : ".") + std::string(key);
  return yaml::ToNestedMatrix(*node, file, name, rows, cols);
}

}  // namespace

Expected<LoadedCalibration> LoadDsecCalibration(const std::string& file) {
  Expected<YAML::Node> root = yaml::LoadFile(file);
  if (!root) return root.status();

  Expected<CameraIntrinsics> cam0 = ReadDsecIntrinsics(*root, "cam0", file, true);
  if (!cam0) return cam0.status();
  Expected<CameraIntrinsics> cam3 = ReadDsecIntrinsics(*root, "cam3", file, true);
  if (!cam3) return cam3.status();
  Expected<CameraIntrinsics> rect0 = ReadDsecIntrinsics(*root, "camRect0", file, false);
  if (!rect0) return rect0.status();
  Expected<CameraIntrinsics> rect3 = ReadDsecIntrinsics(*root, "camRect3", file, false);
  if (!rect3) return rect3.status();

  Expected<Eigen::MatrixXd> T10 = ReadMatrix(*root, {"extrinsics", "T_10"}, file, 4, 4);
  if (!T10) return T10.status();
  Expected<Eigen::MatrixXd> T21 = ReadMatrix(*root, {"extrinsics", "T_21"}, file, 4, 4);
  if (!T21) return T21.status();
  Expected<Eigen::MatrixXd> T32 = ReadMatrix(*root, {"extrinsics", "T_32"}, file, 4, 4);
  if (!T32) return T32.status();
  Expected<Eigen::MatrixXd> R0 = ReadMatrix(*root, {"extrinsics", "R_rect0"}, file, 3, 3);
  if (!R0) return R0.status();
  Expected<Eigen::MatrixXd> R3 = ReadMatrix(*root, {"extrinsics", "R_rect3"}, file, 3, 3);
  if (!R3) return R3.status();
  Expected<Eigen::MatrixXd> Q = ReadMatrix(*root, {"disparity_to_depth", "cams_03"}, file, 4, 4);
  if (!Q) return Q.status();

  AAVIO_RETURN_IF_ERROR(geometry::ValidateRotation(*R0, "extrinsics.R_rect0").WithContext(file));
  AAVIO_RETURN_IF_ERROR(geometry::ValidateRotation(*R3, "extrinsics.R_rect3").WithContext(file));
  // Q = [1 0 0 −cx; 0 1 0 −cy; 0 0 0 f; 0 0 1/b 0] (OpenCV reprojectImageTo3D), b = 1/Q[3][2].
  if (!((*Q)(3, 2) > 0.0)) {
    return ParseError(file + ": disparity_to_depth.cams_03[3][2] = " + StrFormat("%g", (*Q)(3, 2)) +
                      " must be 1/baseline > 0");
  }
  const double baseline_m = 1.0 / (*Q)(3, 2);

  for (const auto* T : {&*T10, &*T21, &*T32}) {
    if (T->row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
      return ParseError(file +
                        ": extrinsics T_10, T_21 and T_32 must be 4x4 rigid transforms "
                        "with last row [0, 0, 0, 1]");
    }
  }
  const Eigen::Matrix4d T30 = *T32 * *T21 * *T10;  // cam0 → cam3 (docs/io.md)

  Expected<geometry::CameraModel> left = geometry::CameraModel::Create(*cam0);
  if (!left) return left.status().WithContext(file + ": intrinsics.cam0");
  Expected<geometry::CameraModel> right = geometry::CameraModel::Create(*cam3);
  if (!right) return right.status().WithContext(file + ": intrinsics.cam3");

  geometry::ProjectionMatrix P_left = geometry::ProjectionMatrix::Zero();
  P_left(0, 0) = rect0->fx;
  P_left(1, 1) = rect0->fy;
  P_left(0, 2) = rect0->cx;
  P_left(1, 2) = rect0->cy;
  P_left(2, 2) = 1.0;
  geometry::ProjectionMatrix P_right = geometry::ProjectionMatrix::Zero();
  P_right(0, 0) = rect3->fx;
  P_right(1, 1) = rect3->fy;
  P_right(0, 2) = rect3->cx;
  P_right(1, 2) = rect3->cy;
  P_right(2, 2) = 1.0;
  P_right(0, 3) = -rect3->fx * baseline_m;

  // The file's internal relations (hold to ~1e-6 in the published files): a violation means
  // a corrupted or hand-mixed file, and the rig would be wrong.
  const Eigen::Matrix3d R_30 = T30.topLeftCorner<3, 3>();
  const Eigen::Vector3d t_30 = T30.topRightCorner<3, 1>();
  const double angle = geometry::RotationDistance(
      geometry::Orthonormalize(*R3) * R_30 * geometry::Orthonormalize(*R0).transpose(),
      Eigen::Matrix3d::Identity());
  const Eigen::Vector3d t_rect = *R3 * t_30;
  const double t_error = (t_rect - Eigen::Vector3d(-baseline_m, 0.0, 0.0)).norm();
  if (angle > 1e-3 || t_error > 1e-3) {
    return FailedPrecondition(
        file + ": inconsistent stereo calibration: R_rect3 * R_30 * R_rect0^T is " +
        StrFormat("%.4f deg from identity and R_rect3 * t_30 is %.4f m from (-b, 0, 0) ",
                  angle * 180.0 / M_PI, t_error) +
        StrFormat(
            "with b = 1/Q[3][2] = %.4f m (T_30 = T_32 T_21 T_10); use the cam_to_cam.yaml of one "
            "recording, unmodified",
            baseline_m));
  }

  std::vector<std::string> warnings;
  geometry::StereoRigParams params{
      *left,       *right, *R0, *R3, P_left, P_right, geometry::RigidTransform::FromMatrix(T30),
      std::nullopt};
  Expected<geometry::StereoRig> rig = geometry::StereoRig::Create(std::move(params), &warnings);
  if (!rig) return rig.status().WithContext(file);
  warnings.push_back(file +
                     ": DSEC calibrations hold no IMU extrinsic; give one in the sequence "
                     "description if an IMU is used");
  return LoadedCalibration{std::move(*rig), "dsec", {file}, std::move(warnings)};
}

}  // namespace aavio::io
