#include "aavio/geometry/camera_model.hpp"

#include <Eigen/LU>
#include <cmath>

#include "aavio/common/format.hpp"

namespace aavio::geometry {

const char* DistortionModelName(DistortionModel model) {
  switch (model) {
    case DistortionModel::kNone:
      return "none";
    case DistortionModel::kRadtan:
      return "plumb_bob";
    case DistortionModel::kEquidistant:
      return "equidistant";
  }
  return "?";
}

namespace {

/// The distortion must map the whole image one to one, and not by a factor no lens has: the
/// image's corners and edge midpoints must undistort, the map must keep its orientation on the way
/// out to them, and (for plumb_bob) their distance from the centre may change at most 3-fold.
Status CheckDistortionOverImage(const CameraModel& model) {
  if (model.model() == DistortionModel::kNone) return Status::Ok();
  const CameraIntrinsics& in = model.intrinsics();
  std::string coeffs;
  for (double c : in.coeffs)
    coeffs += (coeffs.empty() ? "" : ", ") + StrFormat("%g", c);
  const std::string which =
      std::string(DistortionModelName(in.model)) + " distortion [" + coeffs + "]";
  const double w = in.width, h = in.height;
  for (const Eigen::Vector2d& pixel :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0), Eigen::Vector2d(0, h), Eigen::Vector2d(w, h),
        Eigen::Vector2d(w / 2, 0), Eigen::Vector2d(w / 2, h), Eigen::Vector2d(0, h / 2),
        Eigen::Vector2d(w, h / 2)}) {
    const Eigen::Vector2d xd((pixel.x() - in.cx) / in.fx, (pixel.y() - in.cy) / in.fy);
    Eigen::Vector2d xn;
    const std::string at = StrFormat("pixel (%g, %g)", pixel.x(), pixel.y());
    if (!model.Undistort(xd, &xn)) {
      return InvalidArgument(which + " cannot be inverted at " + at +
                             ": no lens maps the image like this; check the coefficients' order "
                             "(k1 k2 p1 p2 [k3] for plumb_bob, k1..k4 for equidistant)");
    }
    for (int step = 1; step <= 16; ++step) {
      Eigen::Matrix2d J;
      model.Distort(xn * (step / 16.0), &J);
      if (!(J.determinant() > 0.0)) {
        return InvalidArgument(which + " folds the image over itself between the centre and " + at +
                               "; check the coefficients' order and signs");
      }
    }
    const double ratio = xn.norm() / std::max(xd.norm(), 1e-9);
    if (in.model == DistortionModel::kRadtan && xd.norm() > 1e-3 &&
        !(ratio < 3.0 && ratio > 1.0 / 3.0)) {
      return InvalidArgument(which + " moves " + at +
                             StrFormat(" %.1f-fold", ratio > 1.0 ? ratio : 1.0 / ratio) +
                             (ratio > 1.0 ? " away from" : " towards") +
                             " the centre; no lens distorts that much: check the coefficients' "
                             "order (k1 k2 p1 p2 [k3]) and that they are not in pixels");
    }
  }
  return Status::Ok();
}

}  // namespace

Expected<CameraModel> CameraModel::Create(CameraIntrinsics in) {
  if (in.width <= 0 || in.height <= 0 || in.width > 100000 || in.height > 100000) {
    return InvalidArgument("image size " + std::to_string(in.width) + "x" +
                           std::to_string(in.height) + " is not a sensor size");
  }
  if (!(in.fx > 0.0) || !(in.fy > 0.0) || !std::isfinite(in.fx) || !std::isfinite(in.fy)) {
    return InvalidArgument("focal lengths must be positive (fx = " + std::to_string(in.fx) +
                           ", fy = " + std::to_string(in.fy) + ")");
  }
  // A principal point far outside the image is a unit or layout error, not a real sensor.
  if (!(std::abs(in.cx - 0.5 * in.width) <= in.width) ||
      !(std::abs(in.cy - 0.5 * in.height) <= in.height)) {
    return InvalidArgument("principal point (" + std::to_string(in.cx) + ", " +
                           std::to_string(in.cy) + ") is far outside the " +
                           std::to_string(in.width) + "x" + std::to_string(in.height) + " image");
  }
  for (double c : in.coeffs) {
    if (!std::isfinite(c)) return InvalidArgument("distortion coefficient is not finite");
  }
  switch (in.model) {
    case DistortionModel::kNone:
      for (double c : in.coeffs) {
        if (c != 0.0) return InvalidArgument("distortion model 'none' with non-zero coefficients");
      }
      in.coeffs.clear();
      break;
    case DistortionModel::kRadtan:
      if (in.coeffs.size() != 4 && in.coeffs.size() != 5) {
        return InvalidArgument(
            "plumb_bob (radtan) takes 4 or 5 coefficients k1 k2 p1 p2 [k3], got " +
            std::to_string(in.coeffs.size()));
      }
      in.coeffs.resize(5, 0.0);
      break;
    case DistortionModel::kEquidistant:
      if (in.coeffs.size() != 4) {
        return InvalidArgument("equidistant takes 4 coefficients k1 k2 k3 k4, got " +
                               std::to_string(in.coeffs.size()));
      }
      break;
  }
  CameraModel model(std::move(in));
  AAVIO_RETURN_IF_ERROR(CheckDistortionOverImage(model));
  return model;
}

Eigen::Vector2d CameraModel::Distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J) const {
  const double x = xn.x();
  const double y = xn.y();
  const std::vector<double>& k = in_.coeffs;
  switch (in_.model) {
    case DistortionModel::kNone:
      if (J) J->setIdentity();
      return xn;
    case DistortionModel::kRadtan: {
      const double r2 = x * x + y * y;
      const double radial = 1.0 + r2 * (k[0] + r2 * (k[1] + r2 * k[4]));
      const double p1 = k[2];
      const double p2 = k[3];
      if (J) {
        const double dradial_dr2 = k[0] + r2 * (2.0 * k[1] + 3.0 * r2 * k[4]);
        (*J)(0, 0) = radial + 2.0 * x * x * dradial_dr2 + 2.0 * p1 * y + 6.0 * p2 * x;
        (*J)(0, 1) = 2.0 * x * y * dradial_dr2 + 2.0 * p1 * x + 2.0 * p2 * y;
        (*J)(1, 0) = 2.0 * x * y * dradial_dr2 + 2.0 * p1 * x + 2.0 * p2 * y;
        (*J)(1, 1) = radial + 2.0 * y * y * dradial_dr2 + 6.0 * p1 * y + 2.0 * p2 * x;
      }
      return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
              y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
    }
    case DistortionModel::kEquidistant: {
      const double r2 = x * x + y * y;
      const double r = std::sqrt(r2);
      if (r < 1e-8) {
        // s(r) = θd / r ≈ 1 + (k1 − 1/3) r² near 0.
        if (J) J->setIdentity();
        return xn;
      }
      const double theta = std::atan(r);
      const double t2 = theta * theta;
      const double poly = 1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])));
      const double theta_d = theta * poly;
      const double s = theta_d / r;
      if (J) {
        const double dthetad_dtheta =
            1.0 + t2 * (3.0 * k[0] + t2 * (5.0 * k[1] + t2 * (7.0 * k[2] + t2 * 9.0 * k[3])));
        const double dtheta_dr = 1.0 / (1.0 + r2);
        const double ds_dr = (dthetad_dtheta * dtheta_dr * r - theta_d) / r2;
        const Eigen::Vector2d u(x / r, y / r);  // dr/d(x, y)
        *J = s * Eigen::Matrix2d::Identity() + ds_dr * xn * u.transpose();
      }
      return s * xn;
    }
  }
  return xn;
}

bool CameraModel::Undistort(const Eigen::Vector2d& xd, Eigen::Vector2d* xn) const {
  Eigen::Vector2d x = xd;
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d error = Distort(x, &J) - xd;
    if (error.squaredNorm() < 1e-20) {
      *xn = x;
      return true;
    }
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) return false;
    x -= J.inverse() * error;
    if (!x.allFinite()) return false;
  }
  const Eigen::Vector2d error = Distort(x) - xd;
  *xn = x;
  return error.squaredNorm() < 1e-20;
}

bool CameraModel::Project(const Eigen::Vector3d& p, Eigen::Vector2d* pixel,
                          Eigen::Matrix<double, 2, 3>* J) const {
  if (!(p.z() > 1e-9)) return false;
  const double inv_z = 1.0 / p.z();
  const Eigen::Vector2d xn(p.x() * inv_z, p.y() * inv_z);
  Eigen::Matrix2d J_distort;
  const Eigen::Vector2d xd = Distort(xn, J ? &J_distort : nullptr);
  *pixel = {in_.fx * xd.x() + in_.cx, in_.fy * xd.y() + in_.cy};
  if (J) {
    Eigen::Matrix<double, 2, 3> J_norm;
    J_norm << inv_z, 0.0, -xn.x() * inv_z,  //
        0.0, inv_z, -xn.y() * inv_z;
    const Eigen::Matrix2d K = Eigen::Vector2d(in_.fx, in_.fy).asDiagonal();
    *J = K * J_distort * J_norm;
  }
  return true;
}

bool CameraModel::Unproject(const Eigen::Vector2d& pixel, Eigen::Vector3d* ray) const {
  const Eigen::Vector2d xd((pixel.x() - in_.cx) / in_.fx, (pixel.y() - in_.cy) / in_.fy);
  Eigen::Vector2d xn;
  if (!Undistort(xd, &xn)) return false;
  *ray = {xn.x(), xn.y(), 1.0};
  return true;
}

}  // namespace aavio::geometry
