#include "aavio/mapping/out_of_view_check.hpp"

#include <gtest/gtest.h>

#include "aavio/mapping/mapping_test_utils.hpp"

namespace aavio::mapping {
namespace {

// The previous map holds two near patches of surface at disparity 40 px: one at the left border
// (u 5–30: its true matches lie outside the right image) and one in the middle (u 110–130).
struct Scene {
  RectifiedStereo stereo = testing::SmallStereo();
  LocalMap previous;
  geometry::RigidTransform T_world_now;  // identity: the previous map is in the current frame

  Scene() {
    const double rho_near = 40.0 / stereo.fb();
    for (int v = 50; v <= 70; ++v) {
      for (int u : {5, 10, 15, 20, 25, 30, 110, 120, 130})
        previous.points_world.push_back(stereo.Backproject(u, v, rho_near));
    }
  }
  Match At(float u, float v, double disparity) const {
    return {u, v, disparity / stereo.fb(), 0.0, StereoKind::kStatic, false};
  }
  std::vector<Match> Kept(std::vector<Match> matches, int radius_px = 4) const {
    DropOutOfViewMatches(previous, T_world_now, stereo, 7, radius_px, &matches);
    return matches;
  }
};

TEST(OutOfViewCheck, DropsFarMatchesWhereTheMapSeesANearSurfaceOutOfTheRightView) {
  const Scene scene;
  // At the border, 10 px of disparity where the map says 40: the true match is off the image.
  EXPECT_TRUE(scene.Kept({scene.At(20, 60, 10.0)}).empty());
  EXPECT_TRUE(scene.Kept({scene.At(33, 60, 10.0)}).empty());  // 3 px from the nearest point
  // Within 20 % of the surface: kept.
  EXPECT_EQ(scene.Kept({scene.At(20, 60, 35.0)}).size(), 1u);
  // Beyond the radius, or where the map knows nothing: kept.
  EXPECT_EQ(scene.Kept({scene.At(20, 80, 10.0)}).size(), 1u);
  EXPECT_EQ(scene.Kept({scene.At(36, 60, 10.0)}, 4).size(), 1u);
  EXPECT_EQ(scene.Kept({scene.At(80, 60, 10.0)}).size(), 1u);
  // A near surface whose matches are in view says nothing of a farther match beside it (an
  // occlusion boundary): kept.
  EXPECT_EQ(scene.Kept({scene.At(120, 60, 10.0)}).size(), 1u);
  // The order of the kept ones stays.
  const std::vector<Match> kept =
      scene.Kept({scene.At(80, 60, 10.0), scene.At(20, 60, 10.0), scene.At(120, 60, 10.0)});
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].u, 80.0f);
  EXPECT_EQ(kept[1].u, 120.0f);
}

// The previous map is moved into the current frame: after the camera moved 0.5 m to the left,
// the surfaces (at 0.6·536/40 = 8.04 m) appear 0.5·536/8.04 = 33 px further right — the border
// patch at u 38–63, still too near for the right view there, the middle one at u 143–163.
TEST(OutOfViewCheck, MovesThePreviousMapIntoTheCurrentView) {
  Scene scene;
  scene.T_world_now.t = {-0.5, 0.0, 0.0};
  EXPECT_TRUE(scene.Kept({scene.At(45, 60, 10.0)}).empty());
  EXPECT_EQ(scene.Kept({scene.At(20, 60, 10.0)}).size(), 1u);  // the border patch left here
}

}  // namespace
}  // namespace aavio::mapping
