#pragma once
// A synthetic registration scene for tests and benchmarks: 3-D edge segments in view and the
// idealised negative time surface a camera sees of them.

#include <Eigen/Core>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/tracking/registration.hpp"

namespace aavio::tracking::testing {

inline const Camera kCamera{240, 180, 200.0, 120.0, 90.0};

// A scene of 3-D line segments (edges of every orientation) at 2–6 m, sampled into map points.
inline std::vector<Eigen::Vector3d> EdgeMap(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // Inside the view (as a map built from it is): |x/z| < 0.45, |y/z| < 0.33.
  std::uniform_real_distribution<double> x(-0.45, 0.45), y(-0.33, 0.33), z(2.0, 6.0), a(0.0, M_PI);
  std::vector<Eigen::Vector3d> points;
  for (int s = 0; s < 60; ++s) {
    const double depth = z(rng);
    const double v = y(rng), u = x(rng);  // y first: the order this scene was first drawn in
    const Eigen::Vector3d c(u * depth, v * depth, depth);
    const double angle = a(rng);
    const Eigen::Vector3d dir(std::cos(angle), std::sin(angle), 0.2 * std::cos(3 * angle));
    for (double l = -0.1; l <= 0.1; l += 0.005)
      points.push_back(c + l * depth * dir.normalized());
  }
  return points;
}

struct Images {
  cv::Mat negative, du, dv, valid;
};

// The negative TS a camera at T_ref_cur sees, idealised: 255·(1 − exp(−d/6 px)) with d the distance
// to the nearest projected map point — dark on the edges, a slope around them (the basin a
// decaying TS gives), and no darkening where edges crowd (which would bias the minimum).
inline Images Render(const std::vector<Eigen::Vector3d>& points,
                     const geometry::RigidTransform& T_ref_cur) {
  cv::Mat not_edge(kCamera.height, kCamera.width, CV_8UC1, cv::Scalar(255));
  const geometry::RigidTransform T_cur_ref = T_ref_cur.Inverse();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = T_cur_ref * p;
    const long u = std::lround(kCamera.f * q.x() / q.z() + kCamera.cx);
    const long v = std::lround(kCamera.f * q.y() / q.z() + kCamera.cy);
    if (u >= 0 && v >= 0 && u < kCamera.width && v < kCamera.height)
      not_edge.at<std::uint8_t>(v, u) = 0;
  }
  cv::Mat distance;
  cv::distanceTransform(not_edge, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat negative_f(distance.size(), CV_32FC1);
  for (int v = 0; v < distance.rows; ++v)
    for (int u = 0; u < distance.cols; ++u)
      negative_f.at<float>(v, u) = static_cast<float>(
          255.0 * (1.0 - std::exp(-static_cast<double>(distance.at<float>(v, u)) / 6.0)));
  Images images;
  negative_f.convertTo(images.negative, CV_8U);
  cv::Sobel(negative_f, images.du, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(negative_f, images.dv, CV_32F, 0, 1, 3, 1.0 / 8.0);
  images.valid = cv::Mat(kCamera.height, kCamera.width, CV_8UC1, cv::Scalar(255));
  return images;
}

}  // namespace aavio::tracking::testing
