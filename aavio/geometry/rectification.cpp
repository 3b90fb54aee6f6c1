#include "aavio/geometry/rectification.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace aavio::geometry {

RectificationMaps BuildRectificationMaps(const CameraModel& raw, const Eigen::Matrix3d& R_rect_raw,
                                         const ProjectionMatrix& P) {
  const int width = raw.width();
  const int height = raw.height();
  const Eigen::Matrix3d K_rect = P.leftCols<3>();
  const Eigen::Matrix3d K_rect_inv = K_rect.inverse();
  const Eigen::Matrix3d R_raw_rect = R_rect_raw.transpose();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

  RectificationMaps maps;
  maps.event_lut.create(height, width, CV_32FC2);
  maps.remap_x.create(height, width, CV_32FC1);
  maps.remap_y.create(height, width, CV_32FC1);
  // Rows are independent (each pixel's iterative undistortion is the startup cost at 1280×720).
  tbb::parallel_for(
      tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
          auto* lut_row = maps.event_lut.ptr<cv::Vec2f>(y);
          auto* map_x_row = maps.remap_x.ptr<float>(y);
          auto* map_y_row = maps.remap_y.ptr<float>(y);
          for (int x = 0; x < width; ++x) {
            // Raw → rectified: undistort, rotate, project with K'.
            Eigen::Vector3d ray;
            lut_row[x] = cv::Vec2f(kNaN, kNaN);
            if (raw.Unproject(Eigen::Vector2d(x, y), &ray)) {
              const Eigen::Vector3d p_rect = K_rect * (R_rect_raw * ray);
              if (p_rect.z() > 1e-9) {
                lut_row[x] = cv::Vec2f(static_cast<float>(p_rect.x() / p_rect.z()),
                                       static_cast<float>(p_rect.y() / p_rect.z()));
              }
            }
            // Rectified → raw: back-project with K'⁻¹, rotate back, distort and project.
            Eigen::Vector2d pixel(-1.0, -1.0);
            const Eigen::Vector3d p_raw = R_raw_rect * (K_rect_inv * Eigen::Vector3d(x, y, 1.0));
            if (!raw.Project(p_raw, &pixel)) pixel = {-1e6, -1e6};  // behind the camera: invalid
            map_x_row[x] = static_cast<float>(pixel.x());
            map_y_row[x] = static_cast<float>(pixel.y());
          }
        }
      });
  const cv::Mat ones(height, width, CV_32FC1, cv::Scalar(1.0f));
  cv::Mat coverage;
  cv::remap(ones, coverage, maps.remap_x, maps.remap_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar(0.0));
  const double threshold = raw.model() == DistortionModel::kEquidistant ? 0.1 : 0.999;
  maps.valid_mask = coverage > threshold;  // 0 or 255
  // Raw pixels whose rectified position (rounded) lies on a valid rectified pixel.
  maps.raw_valid = cv::Mat(height, width, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const cv::Vec2f r = maps.event_lut.at<cv::Vec2f>(y, x);
      if (!(r[0] >= 0.0f && r[1] >= 0.0f)) continue;  // also NaN
      const int u = static_cast<int>(r[0] + 0.5f), v = static_cast<int>(r[1] + 0.5f);
      if (u < width && v < height && maps.IsValid(u, v))
        maps.raw_valid.at<std::uint8_t>(y, x) = 255;
    }
  }
  return maps;
}

StereoRectification BuildStereoRectification(const StereoRig& rig) {
  return {BuildRectificationMaps(rig.left(), rig.R_rect_left_left(), rig.P_left()),
          BuildRectificationMaps(rig.right(), rig.R_rect_right_right(), rig.P_right())};
}

}  // namespace aavio::geometry
