// Costs of tracking on one thread (issue: one registration step ≤ 1.5 ms with 2k points;
// gyroscope pre-integration < 20 µs per tick). The scene is the synthetic one of the tracking
// tests (tracking/synthetic_scene.hpp): 2.4k map points on edges at 2–6 m, a 2° / 5 cm start.
#include <benchmark/benchmark.h>

#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/gyro_preintegration.hpp"
#include "aavio/tracking/registration.hpp"
#include "aavio/tracking/synthetic_scene.hpp"

namespace {

using namespace aavio;

void BM_RegistrationStep(benchmark::State& state) {
  const std::vector<Eigen::Vector3d> map = tracking::testing::EdgeMap(5);
  geometry::RigidTransform truth;
  truth.t = {0.03, 0.01, 0.05};
  const tracking::testing::Images images = tracking::testing::Render(map, truth);
  const tracking::RegistrationImages input{images.negative, images.du, images.dv, images.valid};
  tracking::TrackingConfig config;  // 2000 points, batches of 300, 10 LM steps
  geometry::RigidTransform start = truth;
  start.R = geometry::ExpSO3(Eigen::Vector3d(0.02, -0.02, 0.01));
  std::uint64_t seed = 0;
  int iterations = 0;
  for (auto _ : state) {
    const tracking::Registration registration(map, tracking::testing::kCamera, config, ++seed);
    const tracking::RegistrationResult result = registration.Solve(input, start);
    iterations += result.iterations;
    benchmark::DoNotOptimize(result.T_ref_cur.t.data());
  }
  state.counters["points"] = static_cast<double>(std::min<std::size_t>(map.size(), 2000));
  state.counters["lm_steps"] =
      static_cast<double>(iterations) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_RegistrationStep)->Unit(benchmark::kMillisecond);

void BM_GyroPreintegrationPerTick(benchmark::State& state) {
  // 1 kHz gyroscope, a 10 ms tick: 11 samples around the interval.
  std::vector<imu::ImuSample> samples;
  for (int k = 0; k <= 12; ++k)
    samples.push_back({k * kNsPerMs, Eigen::Vector3d(0.1 * k, -0.3, 0.7), Eigen::Vector3d::Zero()});
  const Eigen::Vector3d bias(0.01, 0.0, -0.01);
  for (auto _ : state) {
    benchmark::DoNotOptimize(imu::IntegrateGyro(samples, 500'000, 10'500'000, bias));
  }
}
BENCHMARK(BM_GyroPreintegrationPerTick)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
