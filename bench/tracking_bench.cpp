// Costs of tracking on one thread (issue: one registration step ≤ 1.5 ms with 2k points;
// gyroscope pre-integration < 20 µs per tick; the stereo check per drawn point). The scene is the
// synthetic one of the tracking tests (tracking/synthetic_scene.hpp): 2.4k map points on edges at
// 2–6 m, a 2° / 5 cm start.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/gyro_preintegration.hpp"
#include "aavio/tracking/registration.hpp"
#include "aavio/tracking/stereo_check.hpp"
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

// The stereo check on 2000 points of a VGA pair (f·b 300 px·m, disparities 0–100): a wall at
// disparity 40 that the right time surface shows (arg 0: nearly every point passes its own
// disparity, as on a static scene) or a right time surface of something else (arg 1: every point
// also searches its row, as behind a person).
void BM_StereoCheckPerPoint(benchmark::State& state) {
  const tracking::Camera camera{640, 480, 500.0, 320.0, 240.0};
  const tracking::StereoCheckRig rig{300.0, 0.0, 0, 100, 0.1};
  constexpr int kDisparity = 40;
  cv::RNG rng(3);
  cv::Mat noise(camera.height, camera.width + kDisparity, CV_32FC1);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(noise, noise, cv::Size(3, 3), 0.0);
  noise.convertTo(noise, CV_8U);
  // right(x) = left(x + d): the wall at disparity d.
  const cv::Mat left = noise(cv::Rect(0, 0, camera.width, camera.height)).clone();
  cv::Mat right = noise(cv::Rect(kDisparity, 0, camera.width, camera.height)).clone();
  if (state.range(0) == 1) rng.fill(right, cv::RNG::UNIFORM, 0, 256);
  const cv::Mat valid(camera.height, camera.width, CV_8UC1, cv::Scalar(255));
  const double z = rig.fb / kDisparity;
  std::mt19937 draw(5);
  std::uniform_real_distribution<double> u_of(0.0, camera.width), v_of(0.0, camera.height);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) {
    const double u = u_of(draw), v = v_of(draw);
    points.emplace_back((u - camera.cx) * z / camera.f, (v - camera.cy) * z / camera.f, z);
  }
  int left_out = 0;
  for (auto _ : state) {
    const tracking::StereoCheck check(left, right, valid, camera, rig);
    for (const Eigen::Vector3d& p : points)
      left_out += check.SeesSomethingElse(p) ? 1 : 0;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["left_out"] =
      static_cast<double>(left_out) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_StereoCheckPerPoint)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
