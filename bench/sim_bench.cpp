// Costs of the simulator's stages: rendering one frame of each preset's left camera in its
// scene, one event-generator step at DSEC resolution, and spline queries.
#include <benchmark/benchmark.h>

#include <random>

#include "aavio/sim/event_generator.hpp"
#include "aavio/sim/motion_spline.hpp"
#include "aavio/sim/motions.hpp"
#include "aavio/sim/presets.hpp"
#include "aavio/sim/renderer.hpp"
#include "aavio/sim/scene_builder.hpp"

namespace {

using namespace aavio;

void BM_RenderFrame(benchmark::State& state, const char* preset_name) {
  const sim::SimulationPreset preset = *sim::GetSimulationPreset(preset_name);
  const geometry::StereoRig rig = *preset.rig();
  const auto poses = preset.motion == sim::MotionKind::kDriving ? sim::DrivingMotion(20, 1)
                                                                : sim::HandHeldMotion(20, 1);
  const sim::Scene scene = sim::BuildScene(preset.scene, poses, sim::BuiltInGravity(), 1.4, 1);
  const sim::Renderer renderer(rig.left());
  sim::RenderedImage image;
  std::size_t k = 0;
  for (auto _ : state) {
    renderer.Render(scene, poses[(k++ * 97) % poses.size()].T_world_body, 0, &image);
    benchmark::DoNotOptimize(image.intensity.data());
  }
  state.SetItemsProcessed(state.iterations() * rig.width() * rig.height());
}
BENCHMARK_CAPTURE(BM_RenderFrame, mini, "mini")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame, rpg, "rpg")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame, mvsec, "mvsec")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame, dsec, "dsec")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame, vector, "vector")->Unit(benchmark::kMillisecond);

void BM_EventStepDsec(benchmark::State& state) {
  const int w = 640, h = 480;
  sim::EventGenerator generator(w, h, {}, 1);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> value(0.05f, 1.0f);
  std::vector<float> a(w * h), b(w * h);
  for (float& v : a)
    v = value(rng);
  for (std::size_t i = 0; i < b.size(); ++i)
    b[i] = i % 10 == 0 ? 1.3f * a[i] : a[i];  // 10 % of pixels cross one threshold (~1 px motion)
  generator.Reset(a, 0);
  std::vector<events::Event> out;
  TimeNs t = 0;
  for (auto _ : state) {
    out.clear();
    t += kNsPerMs;
    generator.Step((t / kNsPerMs) % 2 ? b : a, t, &out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * w * h);
}
BENCHMARK(BM_EventStepDsec)->Unit(benchmark::kMillisecond);

void BM_SplineQuery(benchmark::State& state) {
  const sim::MotionSpline spline = *sim::MotionSpline::Fit(sim::HandHeldMotion(20, 1));
  TimeNs t = 0;
  for (auto _ : state) {
    t = (t + 123'457) % (20 * kNsPerS);
    benchmark::DoNotOptimize(spline.Pose(t));
    benchmark::DoNotOptimize(spline.AngularVelocity(t));
  }
}
BENCHMARK(BM_SplineQuery);

}  // namespace

BENCHMARK_MAIN();
