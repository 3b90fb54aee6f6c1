#include "aavio/sim/scene_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "aavio/sim/motions.hpp"

namespace aavio::sim {
namespace {

/// Distances from the start camera (the origin) along rays in a cone of `half_angle_rad` around
/// the forward axis (+z); rays that hit nothing are left out.
std::vector<double> DepthsAhead(const Scene& scene, double half_angle_rad) {
  std::vector<double> depths;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) {
      const Eigen::Vector3d dir = Eigen::Vector3d(std::tan(half_angle_rad * i / 10.0),
                                                  std::tan(half_angle_rad * j / 10.0), 1.0)
                                      .normalized();
      Hit hit;
      if (scene.Intersect(Eigen::Vector3d::Zero(), dir, &hit))
        depths.push_back(dir.z() * hit.distance);
    }
  }
  return depths;
}

double Quantile(std::vector<double> v, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * (v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

/// Nearest surface in any direction from the origin.
double Clearance(const Scene& scene) {
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 80; ++j) {
      const double polar = M_PI * (i + 0.5) / 40, azimuth = 2 * M_PI * j / 80;
      const Eigen::Vector3d dir(std::sin(polar) * std::cos(azimuth),
                                std::sin(polar) * std::sin(azimuth), std::cos(polar));
      Hit hit;
      if (scene.Intersect(Eigen::Vector3d::Zero(), dir, &hit))
        nearest = std::min(nearest, hit.distance);
    }
  }
  return nearest;
}

TEST(SceneBuilder, IndoorScenesSurroundTheStartAtTheirDatasetsDepths) {
  // What the start camera sees ahead (a 40° cone, the datasets' fields of view): the far wall at
  // the scene's depth (TUM-VIE's office 2.4 m, VECtor's lab 3.5 m, rpg's room 4.5 m, MVSEC's
  // hall 10 m), furniture in front of it over a share of the view, the nearest tenth of the view
  // at the dataset's working distance (TUM-VIE's desk under a metre), and free space around the
  // camera in every direction.
  struct Expectation {
    SceneKind kind;
    double wall_m, nearest_lo_m, nearest_hi_m, in_front_min, clearance_m;
  };
  for (const Expectation& e : {Expectation{SceneKind::kOffice, 2.4, 0.6, 1.2, 0.5, 0.6},
                               Expectation{SceneKind::kLab, 3.5, 0.9, 1.5, 0.2, 1.0},
                               Expectation{SceneKind::kRoom, 4.5, 1.0, 3.5, 0.2, 0.7},
                               Expectation{SceneKind::kHall, 10.0, 3.0, 7.0, 0.3, 1.4}}) {
    for (std::uint64_t seed : {1, 2, 3}) {
      SCOPED_TRACE(::testing::Message()
                   << "scene kind " << static_cast<int>(e.kind) << ", seed " << seed);
      const Scene scene = BuildScene(e.kind, {}, BuiltInGravity(), 1.4, seed);
      const std::vector<double> ahead = DepthsAhead(scene, 20.0 * M_PI / 180.0);
      ASSERT_EQ(ahead.size(), 21u * 21u);
      const double wall = *std::max_element(ahead.begin(), ahead.end());
      const double in_front =
          static_cast<double>(
              std::count_if(ahead.begin(), ahead.end(), [&](double d) { return d < wall - 0.3; })) /
          static_cast<double>(ahead.size());
      EXPECT_NEAR(wall, e.wall_m, 0.05);
      EXPECT_GE(in_front, e.in_front_min);
      EXPECT_GT(Quantile(ahead, 0.1), e.nearest_lo_m);
      EXPECT_LT(Quantile(ahead, 0.1), e.nearest_hi_m);
      EXPECT_GT(Clearance(scene), e.clearance_m);
    }
  }
}

TEST(SceneBuilder, PlanesAreAFewTexturedPlanesAheadOfTheCamera) {
  for (std::uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE(seed);
    const Scene scene = BuildPlanes(seed);
    EXPECT_EQ(scene.quads().size(), 4u);  // back wall, floor, two panels
    const std::vector<double> ahead = DepthsAhead(scene, 20.0 * M_PI / 180.0);
    ASSERT_EQ(ahead.size(), 21u * 21u);
    EXPECT_NEAR(*std::max_element(ahead.begin(), ahead.end()), 3.5, 0.05);
    EXPECT_GT(*std::min_element(ahead.begin(), ahead.end()), 1.0);
    for (const Quad& q : scene.quads())
      EXPECT_LE(q.texture.contrast, 0.5);  // weak edges
  }
}

TEST(SceneBuilder, SinusoidMotionStartsAtTheOriginMovingAndStaysNearIt) {
  const std::vector<geometry::StampedPose> poses = SinusoidMotion(8.0, 3);
  ASSERT_EQ(poses.size(), 1601u);
  EXPECT_LT(poses.front().T_world_body.t.norm(), 1e-12);
  EXPECT_GT((poses[1].T_world_body.t - poses[0].T_world_body.t).norm(), 1e-4);  // mid-motion
  double path_m = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    path_m += (poses[i].T_world_body.t - poses[i - 1].T_world_body.t).norm();
    EXPECT_LT(poses[i].T_world_body.t.norm(), 0.8);
  }
  EXPECT_GT(path_m, 1.5);
  EXPECT_LT(path_m, 5.0);
}

TEST(SceneBuilder, ScenesAreDeterministicFromTheSeed) {
  for (SceneKind kind : {SceneKind::kOffice, SceneKind::kLab}) {
    const Scene a = BuildScene(kind, {}, BuiltInGravity(), 1.4, 7);
    const Scene b = BuildScene(kind, {}, BuiltInGravity(), 1.4, 7);
    const Scene c = BuildScene(kind, {}, BuiltInGravity(), 1.4, 8);
    ASSERT_EQ(a.quads().size(), b.quads().size());
    for (std::size_t k = 0; k < a.quads().size(); ++k) {
      EXPECT_EQ(a.quads()[k].origin, b.quads()[k].origin);
      EXPECT_EQ(a.quads()[k].texture.seed, b.quads()[k].texture.seed);
    }
    EXPECT_NE(a.quads()[8].origin, c.quads()[8].origin);
  }
}

}  // namespace
}  // namespace aavio::sim
