#include "aavio/mapping/global_cloud.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aavio::mapping {
namespace {

// A map of points at `p_world`, each at inverse depth `rho` in its frame.
LocalMap MapOf(const std::vector<Eigen::Vector3d>& p_world, double rho = 0.5) {
  LocalMap map;
  for (const Eigen::Vector3d& p : p_world) {
    DepthPoint d;
    d.rho = rho;
    map.points.push_back(d);
    map.points_world.push_back(p);
  }
  return map;
}

TEST(GlobalCloud, OnePointPerVoxelTheFirstToArrive) {
  GlobalCloud cloud(0.1);
  std::vector<CloudPoint> added;
  cloud.Add(MapOf({{0.01, 0.01, 1.01}, {0.05, 0.02, 1.03}, {0.25, 0.0, 1.0}, {-0.01, 0, 1}}), 10.0,
            &added);
  ASSERT_EQ(added.size(), 3u);  // the second shares the first's voxel
  EXPECT_EQ(added[0].p_world, Eigen::Vector3f(0.01f, 0.01f, 1.01f));
  EXPECT_EQ(added[1].p_world, Eigen::Vector3f(0.25f, 0.0f, 1.0f));
  EXPECT_EQ(added[2].p_world, Eigen::Vector3f(-0.01f, 0.0f, 1.0f));  // x < 0: the next voxel
  EXPECT_FLOAT_EQ(added[0].inv_depth, 0.5f);
  // A later map over the same voxels adds nothing; points beyond max_depth_m are left out.
  added.clear();
  cloud.Add(MapOf({{0.02, 0.03, 1.04}, {3.0, 3.0, 3.0}}), 10.0, &added);
  cloud.Add(MapOf({{5.0, 5.0, 5.0}}, /*rho=*/0.05), 10.0, &added);  // 20 m away
  ASSERT_EQ(added.size(), 1u);
  EXPECT_EQ(added[0].p_world, Eigen::Vector3f(3.f, 3.f, 3.f));
  EXPECT_EQ(cloud.size(), 4u);
}

TEST(GlobalCloud, RemembersTheRecentVoxelsOnly) {
  GlobalCloud cloud(1.0);
  std::vector<CloudPoint> added;
  const std::size_t n = GlobalCloud::kGeneration;
  auto walk = [&](std::size_t from, std::size_t to) {  // voxels (i, 0, 0)
    std::vector<Eigen::Vector3d> p;
    for (std::size_t i = from; i < to; ++i)
      p.emplace_back(static_cast<double>(i) + 0.5, 0.5, 0.5);
    added.clear();
    cloud.Add(MapOf(p), 10.0, &added);
    return added.size();
  };
  EXPECT_EQ(walk(0, n), n);                 // a first generation, full
  EXPECT_EQ(walk(0, 10), 0u);               // known
  EXPECT_EQ(walk(n, 2 * n - 10), n - 10);   // a second
  EXPECT_EQ(walk(0, 10), 0u);               // the first is remembered; these move to the second
  EXPECT_EQ(walk(2 * n, 2 * n + 10), 10u);  // a third: the first is forgotten
  EXPECT_EQ(walk(n, n + 10), 0u);           // the second is remembered
  EXPECT_EQ(walk(0, 10), 0u);               // with the voxels that moved into it
  EXPECT_EQ(walk(10, 20), 10u);             // the first's other voxels come back, once
  EXPECT_EQ(walk(10, 20), 0u);
  EXPECT_EQ(cloud.size(), 2 * n + 10);
}

}  // namespace
}  // namespace aavio::mapping
