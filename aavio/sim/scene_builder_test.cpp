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
  // Depth ahead of the start camera (a 40° cone, the field of view of the datasets' lenses) as
  // the datasets see it: TUM-VIE's desk about a metre away, VECtor's lab 1.5–3.5 m, rpg's room
  // and MVSEC's hall farther: the quartiles of depth lie in [lo, hi]. The camera starts in free
  // space, enclosed in every direction.
  struct Expectation {
    SceneKind kind;
    double lo_m, hi_m, clearance_m;
  };
  for (const Expectation& e :
       {Expectation{SceneKind::kOffice, 0.6, 2.5, 0.6},
        Expectation{SceneKind::kLab, 1.2, 3.55, 1.0}, Expectation{SceneKind::kRoom, 0.8, 4.55, 0.7},
        Expectation{SceneKind::kHall, 3.0, 12.0, 1.4}}) {
    for (std::uint64_t seed : {1, 2, 3}) {
      const Scene scene = BuildScene(e.kind, {}, BuiltInGravity(), 1.4, seed);
      const std::vector<double> ahead = DepthsAhead(scene, 20.0 * M_PI / 180.0);
      ASSERT_EQ(ahead.size(), 21u * 21u) << static_cast<int>(e.kind) << " seed " << seed;
      const double near = Quantile(ahead, 0.25), far = Quantile(ahead, 0.75);
      EXPECT_GT(near, e.lo_m) << static_cast<int>(e.kind) << " seed " << seed;
      EXPECT_LT(far, e.hi_m) << static_cast<int>(e.kind) << " seed " << seed;
      EXPECT_GT(Clearance(scene), e.clearance_m) << static_cast<int>(e.kind) << " seed " << seed;
    }
  }
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
