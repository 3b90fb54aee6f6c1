#include "aavio/sim/scene.hpp"

#include <gtest/gtest.h>

#include <random>

#include "aavio/geometry/random_draws.hpp"
#include "aavio/sim/renderer.hpp"
#include "tests/fixtures/cameras.hpp"

namespace aavio::sim {
namespace {

Quad Plane(const Eigen::Vector3d& centre, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
           double size, Pattern pattern = Pattern::kTiles) {
  Quad q;
  q.origin = centre - (u + v) * size / 2.0;
  q.edge_u = u * size;
  q.edge_v = v * size;
  q.texture.pattern = pattern;
  return q;
}

TEST(Renderer, DepthOfAKnownPlaneIsAnalytic) {
  // A tilted plane n·p = d seen through the strongly distorted rpg lens: every pixel's depth is
  // z = d / (n·r) · r_z for its ray r.
  const geometry::CameraModel camera = testing::RpgLeft().Model();
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const double d = 2.5;
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  Scene scene;
  scene.AddQuad(Plane(n * d, u, v, 100.0));
  scene.Build();
  RenderedImage image;
  Renderer(camera).Render(scene, {}, 0, &image);
  int checked = 0;
  for (int y = 0; y < camera.height(); y += 3) {
    for (int x = 0; x < camera.width(); x += 3) {
      Eigen::Vector3d ray;
      ASSERT_TRUE(camera.Unproject(Eigen::Vector2d(x, y), &ray));
      const double z = d / n.dot(ray);  // ray has z = 1
      EXPECT_NEAR(image.depth_m[static_cast<std::size_t>(y) * camera.width() + x], z, 1e-5 * z);
      ++checked;
    }
  }
  EXPECT_GT(checked, 4000);
}

TEST(Renderer, PoseMovesTheWorldNotTheCamera) {
  Scene scene;
  scene.AddQuad(Plane({0, 0, 4}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 50.0));
  scene.Build();
  const geometry::CameraModel camera = testing::DsecLeft().Model();
  RenderedImage image;
  // Camera 1.5 m forward: the fronto-parallel plane is 2.5 m away at every pixel.
  Renderer(camera).Render(scene, {Eigen::Matrix3d::Identity(), {0, 0, 1.5}}, 0, &image);
  for (float z : image.depth_m)
    EXPECT_NEAR(z, 2.5f, 1e-5f);
}

TEST(Scene, BvhFindsTheSameNearestHitAsBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-10, 10), unit(-1, 1);
  Scene scene;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d n = geometry::DrawZyx(unit, rng).normalized();
    const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
    const double side = 1.0 + 3.0 * (unit(rng) + 1.0);  // drawn before the centre
    scene.AddQuad(Plane({pos(rng), pos(rng), pos(rng)}, u, v, side));
  }
  scene.AddBox({geometry::ExpSO3({0.1, 0.2, 0.3}), {1, 2, 3}}, {2, 1, 3}, {Texture{}});
  scene.Build();
  int hits = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d o = geometry::DrawZyx(pos, rng);
    const Eigen::Vector3d dir = geometry::DrawZyx(unit, rng).normalized();
    Hit bvh;
    const bool found = scene.Intersect(o, dir, &bvh);
    // Brute force over every quad.
    double best = std::numeric_limits<double>::infinity();
    for (const Quad& q : scene.quads()) {
      const Eigen::Vector3d nn = q.edge_u.cross(q.edge_v);
      const double denom = nn.dot(dir);
      if (std::abs(denom) < 1e-12) continue;
      const double s = nn.dot(q.origin - o) / denom;
      if (s <= 1e-6) continue;
      const Eigen::Vector3d p = o + s * dir - q.origin;
      const double a = p.dot(q.edge_u) / q.edge_u.squaredNorm();
      const double b = p.dot(q.edge_v) / q.edge_v.squaredNorm();
      if (a >= 0 && a <= 1 && b >= 0 && b <= 1) best = std::min(best, s);
    }
    ASSERT_EQ(found, std::isfinite(best)) << k;
    if (found) {
      EXPECT_NEAR(bvh.distance, best, 1e-9);
      ++hits;
    }
  }
  EXPECT_GT(hits, 200);
}

TEST(Texture, PrefilteredAlbedoEqualsTheAverageOverThePixel) {
  // The analytic box filter must agree with brute-force supersampling of the sharp texture:
  // that is what keeps edges from aliasing into false events.
  for (Pattern pattern :
       {Pattern::kBricks, Pattern::kTiles, Pattern::kStripes, Pattern::kBlobs, Pattern::kWindows}) {
    Texture t;
    t.pattern = pattern;
    t.angle_rad = 0.3;
    t.seed = 9;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> where(-5, 5);
    double worst = 0.0, total = 0.0;
    const int samples = 300;
    for (int k = 0; k < samples; ++k) {
      const double u = where(rng), v = where(rng), w = 0.02;
      double sum = 0.0;
      const int n = 24;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          sum += t.Albedo(u + w * ((i + 0.5) / n - 0.5), v + w * ((j + 0.5) / n - 0.5), 1e-6);
        }
      }
      const double error = std::abs(sum / (n * n) - t.Albedo(u, v, w));
      worst = std::max(worst, error);
      total += error;
    }
    // Exact for a single straight edge; rectangle corners (min of two edge distances) and
    // neighbouring cells add a little where they fall inside the footprint.
    EXPECT_LT(worst, 0.15) << static_cast<int>(pattern);
    EXPECT_LT(total / samples, 0.01) << static_cast<int>(pattern);
  }
}

TEST(Texture, IsDeterministicAndVariesWithTheSeed) {
  Texture a, b, c;
  a.seed = b.seed = 3;
  c.seed = 4;
  int differ = 0;
  for (int k = 0; k < 100; ++k) {
    const double u = 0.37 * k, v = 0.11 * k;
    EXPECT_EQ(a.Albedo(u, v, 0.01), b.Albedo(u, v, 0.01));
    differ += a.Albedo(u, v, 0.01) != c.Albedo(u, v, 0.01);
  }
  EXPECT_GT(differ, 50);
}

}  // namespace
}  // namespace aavio::sim

namespace aavio::sim {
namespace {

// The rasteriser must see exactly what ray casting through the BVH sees.
TEST(Renderer, RasterisationMatchesRayCasting) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-4, 4), unit(-1, 1);
  Scene scene;
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector3d n = geometry::DrawZyx(unit, rng).normalized();
    const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
    const double side = 0.5 + 2.0 * (unit(rng) + 1.0);  // drawn before the centre
    Quad q = Plane({pos(rng), pos(rng), pos(rng) + 3.0}, u, v, side);
    q.texture.seed = static_cast<std::uint64_t>(i);
    scene.AddQuad(q);
  }
  scene.Build();
  const geometry::CameraModel camera = testing::RpgLeft().Model();
  const Renderer renderer(camera);
  for (int trial = 0; trial < 3; ++trial) {
    const geometry::RigidTransform T_world_cam(
        geometry::ExpSO3(Eigen::Vector3d(0.2 * trial, -0.1, 0.05)),
        Eigen::Vector3d(0.3 * trial, 0, -1.0));
    RenderedImage image;
    renderer.Render(scene, T_world_cam, 0, &image);
    int compared = 0, differ = 0;
    for (int y = 0; y < camera.height(); ++y) {
      for (int x = 0; x < camera.width(); ++x) {
        Eigen::Vector3d ray;
        ASSERT_TRUE(camera.Unproject(Eigen::Vector2d(x, y), &ray));
        Hit hit;
        const bool found = scene.Intersect(T_world_cam.t, T_world_cam.R * ray.normalized(), &hit);
        const float depth = image.depth_m[static_cast<std::size_t>(y) * camera.width() + x];
        ++compared;
        if (!found) {
          differ += depth != 0.0f;
          continue;
        }
        const double z = hit.distance * ray.normalized().z();
        differ += std::abs(static_cast<double>(depth) - z) > 1e-4 * z;
      }
    }
    // Ties on shared edges may go either way in float; nothing else may differ.
    EXPECT_LT(differ, compared / 1000) << trial;
  }
}

}  // namespace
}  // namespace aavio::sim
