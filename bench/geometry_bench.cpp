// Startup and per-point costs of the camera geometry: building the rectification maps of a
// 640x480 DSEC-like camera, and single-point undistortion / projection.
#include <benchmark/benchmark.h>

#include "aavio/geometry/camera_model.hpp"
#include "aavio/geometry/rectification.hpp"
#include "tests/fixtures/cameras.hpp"

namespace {

using aavio::geometry::CameraModel;

void BM_BuildRectificationMaps(benchmark::State& state) {
  const aavio::testing::RealCamera dsec = aavio::testing::DsecLeft();
  const CameraModel camera = dsec.Model();
  for (auto _ : state) {
    auto maps = aavio::geometry::BuildRectificationMaps(camera, dsec.R_rect, dsec.P);
    benchmark::DoNotOptimize(maps.event_lut.data);
  }
  state.SetItemsProcessed(state.iterations() * 640 * 480);
}
BENCHMARK(BM_BuildRectificationMaps)->Unit(benchmark::kMillisecond);

void BM_UnprojectPixel(benchmark::State& state) {
  const CameraModel camera = aavio::testing::DsecLeft().Model();
  int i = 0;
  for (auto _ : state) {
    Eigen::Vector3d ray;
    const Eigen::Vector2d pixel(i % 640, (i / 640) % 480);
    benchmark::DoNotOptimize(camera.Unproject(pixel, &ray));
    benchmark::DoNotOptimize(ray);
    ++i;
  }
}
BENCHMARK(BM_UnprojectPixel);

void BM_ProjectWithJacobian(benchmark::State& state) {
  const CameraModel camera = aavio::testing::DsecLeft().Model();
  const Eigen::Vector3d p(0.3, -0.2, 2.0);
  for (auto _ : state) {
    Eigen::Vector2d pixel;
    Eigen::Matrix<double, 2, 3> J;
    benchmark::DoNotOptimize(camera.Project(p, &pixel, &J));
    benchmark::DoNotOptimize(J);
  }
}
BENCHMARK(BM_ProjectWithJacobian);

}  // namespace

BENCHMARK_MAIN();
