// Startup and per-point costs of the camera geometry: building the rectification maps of a
// 640x480 DSEC-like camera, and single-point undistortion / projection.
#include <benchmark/benchmark.h>

#include "aavio/geometry/camera_model.hpp"
#include "aavio/geometry/rectification.hpp"

namespace {

using aavio::geometry::CameraIntrinsics;
using aavio::geometry::CameraModel;
using aavio::geometry::DistortionModel;

CameraModel DsecLeft() {
  // zurich_city_04a left event camera (ESVO2 calibration).
  CameraIntrinsics in{640,
                      480,
                      553.469,
                      553.399,
                      346.653,
                      216.521,
                      DistortionModel::kRadtan,
                      {-0.0935648, 0.194458, 7.64243e-05, 0.00195639}};
  return *CameraModel::Create(in);
}

void BM_BuildRectificationMaps(benchmark::State& state) {
  const CameraModel camera = DsecLeft();
  Eigen::Matrix3d R;
  R << 0.999866, -0.00319364, 0.0160517, 0.00322964, 0.999992, -0.00221712, -0.0160445, 0.00226867,
      0.999869;
  aavio::geometry::ProjectionMatrix P;
  P << 536.058, 0, 336.267, 0, 0, 536.058, 222.289, 0, 0, 0, 1, 0;
  for (auto _ : state) {
    auto maps = aavio::geometry::BuildRectificationMaps(camera, R, P);
    benchmark::DoNotOptimize(maps.event_lut.data);
  }
  state.SetItemsProcessed(state.iterations() * 640 * 480);
}
BENCHMARK(BM_BuildRectificationMaps)->Unit(benchmark::kMillisecond);

void BM_UnprojectPixel(benchmark::State& state) {
  const CameraModel camera = DsecLeft();
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
  const CameraModel camera = DsecLeft();
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
