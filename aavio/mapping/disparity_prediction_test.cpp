#include "aavio/mapping/disparity_prediction.hpp"

#include <gtest/gtest.h>

#include "aavio/mapping/mapping_test_utils.hpp"

namespace aavio::mapping {
namespace {

// A previous map of one surface patch at disparity `disparity` (u 60–100, v 40–80), each point
// with inverse-depth standard deviation `sigma_rho`.
LocalMap PatchMap(const RectifiedStereo& stereo, double disparity, double sigma_rho) {
  LocalMap map;
  const double rho = disparity / stereo.fb();
  for (int v = 40; v <= 80; v += 4) {
    for (int u = 60; u <= 100; u += 4) {
      DepthPoint p;
      p.u = static_cast<float>(u), p.v = static_cast<float>(v);
      p.rho = rho;
      p.nu = 3.0;
      p.s2 = sigma_rho * sigma_rho / 3.0;  // σ² = ν/(ν − 2) s²
      map.points.push_back(p);
      map.points_world.push_back(p.Point(stereo));
    }
  }
  return map;
}

TEST(DisparityPrediction, WindowSpansTheNearbyPointsAndTheirUncertainty) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const DisparityRange full{0, 80};
  // A tight map: the window is the narrowest, ±2 px, rounded outwards.
  const DisparityPrediction tight(PatchMap(stereo, 20.5, 1e-6), {}, stereo);
  DisparityRange w;
  ASSERT_TRUE(tight.Window(80.0f, 60.0f, full, &w));
  EXPECT_EQ(w.min, 18);  // ⌊20.5 − 2⌋
  EXPECT_EQ(w.max, 23);  // ⌈20.5 + 2⌉
  // σ_ρ of 2 px of disparity: ±3σ = ±6 px.
  const DisparityPrediction loose(PatchMap(stereo, 20.5, 2.0 / stereo.fb()), {}, stereo);
  ASSERT_TRUE(loose.Window(80.0f, 60.0f, full, &w));
  EXPECT_EQ(w.min, 14);
  EXPECT_EQ(w.max, 27);
  // Cut to the range searched at all.
  ASSERT_TRUE(loose.Window(80.0f, 60.0f, {0, 24}, &w));
  EXPECT_EQ(w.max, 24);
  // Points within a cell or two count; where the map has nothing, no window.
  EXPECT_TRUE(tight.Window(110.0f, 60.0f, full, &w));
  EXPECT_FALSE(tight.Window(130.0f, 60.0f, full, &w));
  EXPECT_FALSE(tight.Window(20.0f, 100.0f, full, &w));
  // A prediction wholly outside the range: none.
  EXPECT_FALSE(tight.Window(80.0f, 60.0f, {30, 80}, &w));
  EXPECT_EQ(tight.covered_cells(), 6 * 6);  // u 60–100 and v 40–80 in 8 px cells: 6 × 6
}

TEST(DisparityPrediction, APixelAtADepthEdgeGetsBothSides) {
  const RectifiedStereo stereo = testing::SmallStereo();
  LocalMap map = PatchMap(stereo, 20.5, 1e-6);
  const LocalMap near = PatchMap(stereo, 50.5, 1e-6);
  for (std::size_t i = 0; i < near.points.size(); ++i) {
    if (near.points[i].u < 100.0f) continue;  // the near surface's column at u = 100 only
    map.points.push_back(near.points[i]);
    map.points_world.push_back(near.points_world[i] +
                               Eigen::Vector3d(8.0 / stereo.f, 0, 0) * near.points_world[i].z());
  }
  const DisparityPrediction prediction(map, {}, stereo);
  DisparityRange w;
  ASSERT_TRUE(prediction.Window(100.0f, 60.0f, {0, 80}, &w));
  EXPECT_EQ(w.min, 18);
  EXPECT_EQ(w.max, 53);
}

TEST(DisparityPrediction, TheMapIsMovedIntoTheCurrentView) {
  // The camera moved forward by a fifth of the surface's depth: its disparity grows by 1 / 0.8.
  const RectifiedStereo stereo = testing::SmallStereo();
  const double z = stereo.fb() / 20.5;
  geometry::RigidTransform T_world_now;
  T_world_now.t = {0.0, 0.0, 0.2 * z};
  const DisparityPrediction prediction(PatchMap(stereo, 20.5, 1e-6), T_world_now, stereo);
  DisparityRange w;
  ASSERT_TRUE(prediction.Window(80.0f, 60.0f, {0, 80}, &w));
  EXPECT_EQ(w.min, 23);  // 20.5 / 0.8 = 25.625, ± 2
  EXPECT_EQ(w.max, 28);
  // Points behind the camera: ignored.
  T_world_now.t = {0.0, 0.0, 2.0 * z};
  EXPECT_EQ(DisparityPrediction(PatchMap(stereo, 20.5, 1e-6), T_world_now, stereo).covered_cells(),
            0);
}

}  // namespace
}  // namespace aavio::mapping
