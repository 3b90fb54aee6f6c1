#include "aavio/tracking/edge_age.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace aavio::tracking {
namespace {

const Camera kCamera{240, 180, 200.0, 119.5, 89.5};

// A row of map points 2 m ahead on image row 100, and a time surface rendered with τ = 30 ms
// whose edge along that row fired `age_ms` ago (one pixel above it fresher, as a trail's front).
struct Scene {
  std::vector<Eigen::Vector3d> points;
  cv::Mat ts;
};
Scene EdgeOfAge(double age_ms) {
  Scene s;
  for (int i = 0; i < 300; ++i)
    s.points.emplace_back((20.0 + 0.6 * i - kCamera.cx) * 2.0 / kCamera.f,
                          (100.0 - kCamera.cy) * 2.0 / kCamera.f, 2.0);
  s.ts = cv::Mat::zeros(180, 240, CV_8UC1);
  s.ts.row(100).setTo(static_cast<int>(std::lround(255.0 * std::exp(-age_ms / 30.0))));
  s.ts.row(99).setTo(static_cast<int>(std::lround(255.0 * std::exp(-(age_ms - 5.0) / 30.0))));
  return s;
}

TEST(EdgeAge, IsTheAgeOfTheFreshestEventBesideEachMapPoint) {
  const Scene s = EdgeOfAge(50.0);
  // The row above is 5 ms fresher: 45 ms, to the rounding of an 8-bit surface.
  EXPECT_NEAR(MedianEdgeAgeMs(s.points, {}, kCamera, s.ts, 30.0), 45.0, 0.2);
  // Nothing beside the points: as old as the bound.
  const cv::Mat empty = cv::Mat::zeros(180, 240, CV_8UC1);
  EXPECT_NEAR(MedianEdgeAgeMs(s.points, {}, kCamera, empty, 30.0), 300.0, 1e-9);
  // No point in view, or none at all.
  const geometry::RigidTransform turned_away(
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix(),
      Eigen::Vector3d::Zero());
  EXPECT_EQ(MedianEdgeAgeMs(s.points, turned_away, kCamera, s.ts, 30.0), -1.0);
  EXPECT_EQ(MedianEdgeAgeMs({}, {}, kCamera, s.ts, 30.0), -1.0);
}

TEST(EdgeAge, DecayIsAtLeastTheConfiguredAndTheEdgesAge) {
  AdaptiveDecay decay(30.0, true);
  EXPECT_EQ(decay.decay_ms(), 30.0);  // nothing measured yet
  decay.AddEdgeAge(8.0);              // fresh edges (a room, a street): τ as configured
  EXPECT_EQ(decay.decay_ms(), 30.0);
  for (double age : {70.0, 65.0, 400.0, 60.0})
    decay.AddEdgeAge(age);
  EXPECT_EQ(decay.decay_ms(), 65.0);  // the median of the last ones
  for (int i = 0; i < 5; ++i)
    decay.AddEdgeAge(1000.0);
  EXPECT_EQ(decay.decay_ms(), 300.0);  // at most 10 τ
  AdaptiveDecay fixed(30.0, false);
  fixed.AddEdgeAge(100.0);
  EXPECT_EQ(fixed.decay_ms(), 30.0);
}

}  // namespace
}  // namespace aavio::tracking
