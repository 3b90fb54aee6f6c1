// ESVO/ESVO2 left.yaml + right.yaml (docs/io.md).
#include <cmath>
#include <cstdio>

#include "aavio/io/calibration.hpp"
#include "aavio/io/yaml_reading.hpp"

namespace aavio::io {

namespace {

using geometry::CameraIntrinsics;
using geometry::CameraModel;
using geometry::DistortionModel;

struct EsvoCameraFile {
  CameraModel camera;
  Eigen::Matrix3d R_rect;
  geometry::ProjectionMatrix P;
  std::optional<yaml::RosMatrix> T_right_left;  // unchecked: see the 9-value rule
  std::optional<geometry::RigidTransform> T_b_c;
  std::vector<std::string> warnings;  // what was assumed to read the file
};

Expected<DistortionModel> ParseDistortionModel(const std::string& name, const std::string& where) {
  if (name == "plumb_bob" || name == "radtan" || name == "radial-tangential") {
    return DistortionModel::kRadtan;
  }
  if (name == "equidistant" || name == "fisheye" || name == "kannala_brandt") {
    return DistortionModel::kEquidistant;
  }
  if (name == "none" || name.empty()) return DistortionModel::kNone;
  return ParseError(where + ": distortion_model '" + name +
                    "' is not supported; use plumb_bob (radtan, 4 or 5 coefficients) or "
                    "equidistant (Kannala-Brandt, 4 coefficients)");
}

Expected<EsvoCameraFile> ReadEsvoCamera(const std::string& file) {
  Expected<YAML::Node> root = yaml::LoadFile(file);
  if (!root) return root.status();
  const YAML::Node& n = *root;
  auto child = [&](const char* key, const char* hint) { return yaml::Child(n, key, file, hint); };
  auto ros = [&](const char* key, int rows, int cols) -> Expected<Eigen::MatrixXd> {
    Expected<YAML::Node> node = child(key, "a {rows, cols, data} matrix");
    if (!node) return node.status();
    Expected<yaml::RosMatrix> m = yaml::ToRosMatrix(*node, file, key);
    if (!m) return m.status();
    return yaml::CheckedRosMatrix(*m, key, rows, cols);
  };

  CameraIntrinsics in;
  Expected<YAML::Node> w = child("image_width", "sensor columns");
  if (!w) return w.status();
  Expected<YAML::Node> h = child("image_height", "sensor rows");
  if (!h) return h.status();
  Expected<int> width = yaml::ToInt(*w, file, "image_width");
  if (!width) return width.status();
  Expected<int> height = yaml::ToInt(*h, file, "image_height");
  if (!height) return height.status();
  in.width = *width;
  in.height = *height;

  Expected<Eigen::MatrixXd> K = ros("camera_matrix", 3, 3);
  if (!K) return K.status();
  if ((*K)(0, 1) != 0.0 || (*K)(1, 0) != 0.0 || (*K)(2, 0) != 0.0 || (*K)(2, 1) != 0.0 ||
      (*K)(2, 2) != 1.0) {
    return ParseError(file + ": camera_matrix must be [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
  }
  in.fx = (*K)(0, 0);
  in.fy = (*K)(1, 1);
  in.cx = (*K)(0, 2);
  in.cy = (*K)(1, 2);

  Expected<YAML::Node> model_node = child("distortion_model", "plumb_bob or equidistant");
  if (!model_node) return model_node.status();
  Expected<std::string> model_name = yaml::ToString(*model_node, file, "distortion_model");
  if (!model_name) return model_name.status();
  Expected<DistortionModel> model =
      ParseDistortionModel(*model_name, yaml::Where(file, *model_node));
  if (!model) return model.status();
  in.model = *model;

  Expected<YAML::Node> dist_node = child("distortion_coefficients", "a {rows: 1, cols: N} matrix");
  if (!dist_node) return dist_node.status();
  Expected<yaml::RosMatrix> dist = yaml::ToRosMatrix(*dist_node, file, "distortion_coefficients");
  if (!dist) return dist.status();
  std::vector<std::string> warnings;
  // VECtor's published files: plumb_bob with 5 values under a 1x4 header. Five values have one
  // reading for plumb_bob (k1 k2 p1 p2 k3); for another model, or another count, the clear error.
  if (*model == DistortionModel::kRadtan && dist->rows == 1 && dist->cols == 4 &&
      dist->data.size() == 5) {
    dist->cols = 5;
    char k3[32];
    std::snprintf(k3, sizeof(k3), "%g", dist->data[4]);
    warnings.push_back(dist->where +
                       ": distortion_coefficients declares 1x4 but lists 5 values; read them as "
                       "plumb_bob k1 k2 p1 p2 k3 (k3 = " +
                       std::string(k3) + "). Set cols: 5 if that is right");
  }
  Expected<Eigen::MatrixXd> dist_checked =
      yaml::CheckedRosMatrix(*dist, "distortion_coefficients", dist->rows, dist->cols);
  if (!dist_checked) return dist_checked.status();
  if (dist->rows != 1 && dist->cols != 1) {
    return ParseError(dist->where + ": distortion_coefficients must be a single row (1xN)");
  }
  in.coeffs = dist->data;

  Expected<CameraModel> camera = CameraModel::Create(in);
  if (!camera) return camera.status().WithContext(file);

  Expected<Eigen::MatrixXd> R = ros("rectification_matrix", 3, 3);
  if (!R) return R.status();
  AAVIO_RETURN_IF_ERROR(geometry::ValidateRotation(*R, "rectification_matrix").WithContext(file));
  Expected<Eigen::MatrixXd> P = ros("projection_matrix", 3, 4);
  if (!P) return P.status();

  EsvoCameraFile out{*camera, *R, *P, std::nullopt, std::nullopt, std::move(warnings)};
  if (YAML::Node t = n["T_right_left"]) {
    Expected<yaml::RosMatrix> m = yaml::ToRosMatrix(t, file, "T_right_left");
    if (!m) return m.status();
    out.T_right_left = *m;
  }
  if (YAML::Node t = n["T_b_c"]) {
    Expected<yaml::RosMatrix> m = yaml::ToRosMatrix(t, file, "T_b_c");
    if (!m) return m.status();
    Expected<Eigen::MatrixXd> Tbc = yaml::CheckedRosMatrix(*m, "T_b_c", 3, 4);
    if (!Tbc) return Tbc.status();
    AAVIO_RETURN_IF_ERROR(
        geometry::ValidateRotation(Tbc->leftCols<3>(), "T_b_c rotation").WithContext(file));
    out.T_b_c = geometry::RigidTransform::FromMatrix(Eigen::Matrix<double, 3, 4>(*Tbc));
  }
  return out;
}

}  // namespace

Expected<LoadedCalibration> LoadEsvoCalibration(const std::string& left_yaml,
                                                const std::string& right_yaml) {
  Expected<EsvoCameraFile> left = ReadEsvoCamera(left_yaml);
  if (!left) return left.status();
  Expected<EsvoCameraFile> right = ReadEsvoCamera(right_yaml);
  if (!right) return right.status();

  std::vector<std::string> warnings = left->warnings;
  warnings.insert(warnings.end(), right->warnings.begin(), right->warnings.end());
  geometry::StereoRigParams params{left->camera, right->camera, left->R_rect, right->R_rect,
                                   left->P,      right->P,      {},           left->T_b_c};

  // The baseline as the rig will compute it, for the derivation rule below.
  const double f = right->P(0, 0);
  const double baseline_m = f > 0.0 ? -right->P(0, 3) / f : 0.0;
  // Rectified right ← rectified left is (I, (−b, 0, 0)), so raw right ← raw left is
  // [R_rect_rightᵀ R_rect_left | R_rect_rightᵀ (−b, 0, 0)ᵀ].
  const Eigen::Matrix3d R_rect_left = geometry::Orthonormalize(left->R_rect);
  const Eigen::Matrix3d R_rect_right = geometry::Orthonormalize(right->R_rect);
  const auto derived_rotation = [&] {
    return Eigen::Matrix3d(R_rect_right.transpose() * R_rect_left);
  };
  const auto derive = [&] {
    params.T_right_left = {derived_rotation(),
                           R_rect_right.transpose() * Eigen::Vector3d(-baseline_m, 0.0, 0.0)};
  };
  if (!left->T_right_left) {
    derive();
    warnings.push_back(left_yaml +
                       ": no T_right_left; derived it from the rectification "
                       "rotations and the baseline in the right projection_matrix");
  } else if (left->T_right_left->rows == 3 && left->T_right_left->cols == 4 &&
             left->T_right_left->data.size() == 9) {
    // ESVO2's DSEC files: a 3x4 declaration holding only the 3x3 rotation.
    derive();
    Eigen::Matrix3d R_file;
    for (int i = 0; i < 9; ++i)
      R_file(i / 3, i % 3) = left->T_right_left->data[i];
    char angle[64];
    std::snprintf(angle, sizeof(angle), "%.3f deg",
                  geometry::RotationDistance(geometry::Orthonormalize(R_file), derived_rotation()) *
                      180.0 / M_PI);
    warnings.push_back(left->T_right_left->where +
                       ": T_right_left declares 3x4 but holds 9 numbers (a rotation only); "
                       "derived the extrinsic from the rectification rotations and the baseline "
                       "in the right projection_matrix (the file's rotation differs from it by " +
                       std::string(angle) + ")");
  } else {
    Expected<Eigen::MatrixXd> T = yaml::CheckedRosMatrix(*left->T_right_left, "T_right_left", 3, 4);
    if (!T) return T.status();
    params.T_right_left = geometry::RigidTransform::FromMatrix(Eigen::Matrix<double, 3, 4>(*T));
  }

  Expected<geometry::StereoRig> rig = geometry::StereoRig::Create(std::move(params), &warnings);
  if (!rig) return rig.status().WithContext(left_yaml + " + " + right_yaml);
  return LoadedCalibration{std::move(*rig), "esvo", {left_yaml, right_yaml}, std::move(warnings)};
}

}  // namespace aavio::io
