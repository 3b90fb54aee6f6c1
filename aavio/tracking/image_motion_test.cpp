#include "aavio/tracking/image_motion.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aavio::tracking {
namespace {

const Camera kCamera{240, 180, 200.0, 119.5, 89.5};

TEST(ImageMotion, SpeedOfASidewaysMoveIsFocalTimesShiftOverDepth) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 500; ++i)
    points.emplace_back(-1.0 + 0.004 * i, 0.2, 2.0);  // a row of points 2 m ahead
  const geometry::RigidTransform a;
  const geometry::RigidTransform b(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.01, 0.0, 0.0));
  // 1 cm sideways at 2 m: 200 · 0.01 / 2 = 1 px, in 10 ms: 100 px/s.
  EXPECT_NEAR(MedianImageSpeed(points, a, b, kCamera, 0.01), 100.0, 1e-6);
  EXPECT_EQ(MedianImageSpeed({}, a, b, kCamera, 0.01), 0.0);
  EXPECT_EQ(MedianImageSpeed(points, a, b, kCamera, 0.0), 0.0);
}

TEST(ImageMotion, DecayLengthensOnlyWhereTheImageMovesSlowly) {
  TimeSurfaceDecay decay(30.0, 3.0);
  EXPECT_EQ(decay.decay_ms(), 30.0);  // no speed yet: the configured τ
  decay.AddSpeed(300.0);              // 3 px in 10 ms: τ stays
  EXPECT_EQ(decay.decay_ms(), 30.0);
  for (int i = 0; i < 5; ++i)
    decay.AddSpeed(50.0);  // 3 px in 60 ms
  EXPECT_NEAR(decay.decay_ms(), 60.0, 1e-9);
  for (int i = 0; i < 5; ++i)
    decay.AddSpeed(0.0);  // at rest: the bound
  EXPECT_EQ(decay.decay_ms(), 300.0);
  decay.Reset();
  EXPECT_EQ(decay.decay_ms(), 30.0);
  TimeSurfaceDecay fixed(30.0, 0.0);
  fixed.AddSpeed(1.0);
  EXPECT_EQ(fixed.decay_ms(), 30.0);
}

}  // namespace
}  // namespace aavio::tracking
