// Costs of the representation stage on one core at 640×480 (issue: TS ≤ 1.0 ms, AA ≤ 1.5 ms,
// sampling ≤ 0.5 ms for ~70k events per tick). The events are real simulator output: 200 ms of
// the dsec preset's street, with time compressed so that a 10 ms tick holds ~70k events (the
// spatial structure of a drive, at the event rate of a fast one).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "aavio/events/adaptive_accumulation.hpp"
#include "aavio/events/edge_sampler.hpp"
#include "aavio/events/representation_builder.hpp"
#include "aavio/events/ts_images.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/sim/event_simulation.hpp"

namespace {

using namespace aavio;

constexpr TimeNs kTick = 10 * kNsPerMs;
constexpr std::size_t kEventsPerTick = 70'000;

struct Workload {
  geometry::StereoRectification rectification;
  int width = 0, height = 0;
  std::vector<events::Event> left, right;  // time-compressed, starting at 0
  TimeNs end_ns = 0;
};

const Workload& GetWorkload() {
  static const Workload workload = [] {
    cv::setNumThreads(1);
    sim::SimulationRequest request;
    request.preset = "dsec";
    request.duration_s = 3.0;
    const sim::SimulationWorld world = *sim::BuildSimulationWorld(request);
    sim::StereoEventSimulation simulation(world, 1);
    const TimeNs t0 = world.spline.t_begin_ns() + SecondsToNs(1.0);  // under way
    simulation.Start(t0);
    Workload w;
    while (simulation.time_ns() < t0 + 200 * kNsPerMs)
      simulation.Step(t0 + 200 * kNsPerMs, &w.left, &w.right);
    // Compress time: kEventsPerTick left events per tick.
    const double scale = static_cast<double>(kEventsPerTick) * static_cast<double>(200 * kNsPerMs) /
                         (static_cast<double>(w.left.size()) * static_cast<double>(kTick));
    for (auto* stream : {&w.left, &w.right}) {
      for (events::Event& e : *stream)
        e.t_ns = static_cast<TimeNs>(static_cast<double>(e.t_ns - t0) / scale);
    }
    w.end_ns = static_cast<TimeNs>(static_cast<double>(200 * kNsPerMs) / scale);
    w.rectification = geometry::BuildStereoRectification(world.rig);
    w.width = world.rig.width();
    w.height = world.rig.height();
    return w;
  }();
  return workload;
}

// Index of the first event after t.
std::size_t After(const std::vector<events::Event>& events, TimeNs t) {
  return static_cast<std::size_t>(
      std::upper_bound(events.begin(), events.end(), t,
                       [](TimeNs v, const events::Event& e) { return v < e.t_ns; }) -
      events.begin());
}

void BM_TimeSurface(benchmark::State& state) {
  const Workload& w = GetWorkload();
  const events::ImageRectifier rectifier(w.rectification.left);
  std::unique_ptr<events::TimeSurface> ts;
  TimeNs tick = 0;
  std::size_t begin = 0;
  cv::Mat padded = rectifier.MakePadded(), rectified;
  cv::Mat raw = events::ImageRectifier::PaddedInterior(padded);
  std::int64_t events = 0;
  for (auto _ : state) {
    if (tick + kTick > w.end_ns || !ts) {
      state.PauseTiming();
      ts = std::make_unique<events::TimeSurface>(w.width, w.height, 0);
      tick = 0, begin = 0;
      state.ResumeTiming();
    }
    tick += kTick;
    const std::size_t end = After(w.left, tick);
    (void)ts->Insert(std::span(w.left).subspan(begin, end - begin));
    events += static_cast<std::int64_t>(end - begin);
    begin = end;
    ts->Render(tick, 30.0, &raw);
    rectifier.RectifyPadded(padded, &rectified);
    events::MedianFilterTs(rectified, &rectified);
    benchmark::DoNotOptimize(rectified.data);
  }
  state.counters["events_per_tick"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_TimeSurface)->Unit(benchmark::kMillisecond);

void BM_NegativeTsAndGradients(benchmark::State& state) {
  const Workload& w = GetWorkload();
  events::TimeSurface ts(w.width, w.height, 0);
  (void)ts.Insert(std::span(w.left).subspan(0, After(w.left, 5 * kTick)));
  cv::Mat raw, negative, du, dv;
  ts.Render(5 * kTick, 30.0, &raw);
  for (auto _ : state) {
    events::NegativeTs(raw, &negative);
    events::SobelGradients(negative, &du, &dv);
    benchmark::DoNotOptimize(dv.data);
  }
}
BENCHMARK(BM_NegativeTsAndGradients)->Unit(benchmark::kMillisecond);

void BM_AaMap(benchmark::State& state) {
  const Workload& w = GetWorkload();
  const events::AdaptiveAccumulationConfig config;
  events::AdaptiveAccumulator accumulator(w.width, w.height, config);
  const events::ImageRectifier rectifier(w.rectification.left);
  events::AaMap map;
  cv::Mat binary, rectified;
  TimeNs tick = 0;
  std::int64_t used = 0, offered = 0;
  for (auto _ : state) {
    tick = tick + kTick > w.end_ns ? kTick : tick + kTick;
    accumulator.Build(w.left, tick, &map);
    binary = map.counts > 0;
    rectifier.Rectify(binary, &rectified);
    used += map.used_events;
    offered += map.window_events;
    benchmark::DoNotOptimize(rectified.data);
  }
  state.counters["events_per_tick"] =
      benchmark::Counter(static_cast<double>(offered), benchmark::Counter::kAvgIterations);
  state.counters["accumulated"] =
      benchmark::Counter(static_cast<double>(used), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_AaMap)->Unit(benchmark::kMillisecond);

void BM_Sampling(benchmark::State& state) {
  const Workload& w = GetWorkload();
  events::AdaptiveAccumulator accumulator(w.width, w.height, {});
  events::AaMap map;
  accumulator.Build(w.left, std::min(3 * kTick, w.end_ns), &map);
  events::EdgeSamplingConfig config;                         // 2500 points, 8×6
  config.min_spacing_px = static_cast<int>(state.range(0));  // 0: the paper, 2: the DSEC preset
  std::uint64_t seed = 0;
  std::size_t samples = 0;
  for (auto _ : state) {
    const auto s = events::SampleAaMap(map, w.rectification.left, config, ++seed);
    samples = s.size();
    benchmark::DoNotOptimize(s.data());
  }
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_Sampling)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_ObservationBothCameras(benchmark::State& state) {
  const Workload& w = GetWorkload();
  std::unique_ptr<events::RepresentationBuilder> builder;
  TimeNs tick = 0;
  std::size_t begin_l = 0, begin_r = 0;
  events::Observation obs;
  for (auto _ : state) {
    if (tick + kTick > w.end_ns || !builder) {
      state.PauseTiming();
      builder = std::make_unique<events::RepresentationBuilder>(w.rectification, w.width, w.height,
                                                                events::RepresentationConfig{}, 0);
      tick = 0, begin_l = 0, begin_r = 0;
      state.ResumeTiming();
    }
    tick += kTick;
    const std::size_t end_l = After(w.left, tick), end_r = After(w.right, tick);
    (void)builder->AddEvents(events::Camera::kLeft,
                             std::span(w.left).subspan(begin_l, end_l - begin_l));
    (void)builder->AddEvents(events::Camera::kRight,
                             std::span(w.right).subspan(begin_r, end_r - begin_r));
    begin_l = end_l, begin_r = end_r;
    (void)builder->Build(tick, &obs);
    benchmark::DoNotOptimize(obs.samples.data());
  }
}
BENCHMARK(BM_ObservationBothCameras)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
