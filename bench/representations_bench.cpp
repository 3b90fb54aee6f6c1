// Costs of the representation stage on one core, per sensor size and event rate: the time
// surface (insertion, render, rectification, median), the rectification alone, its negative and
// gradients, the AA map, the edge samples, and the whole observation of both cameras. The events
// are real simulator output: a stretch of each preset's scene (rpg 240×180, dsec 640×480,
// tum_vie 1280×720), with time compressed or stretched so that a 10 ms tick holds the events per
// camera the benchmark's second argument gives, in thousands (14k: the rpg twins' 1.4 Mev/s;
// 40k: DSEC's 4 Mev/s; 100k: a TUM-VIE desk at 10 Mev/s; 200k: 20 Mev/s, a fast hand-held VGA
// camera or a busy street).
#include <benchmark/benchmark.h>

#include <map>
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
// Benchmark argument 0: the preset, and how much of its motion is simulated how fast — enough
// events for 10 ticks or more at the higher rate below.
struct Sensor {
  const char* preset;
  double seconds, speed;
};
constexpr Sensor kSensors[] = {{"rpg", 1.0, 1.0}, {"dsec", 1.0, 3.0}, {"tum_vie", 0.15, 1.0}};

struct Workload {
  geometry::StereoRectification rectification;
  int width = 0, height = 0;
  std::vector<events::Event> left, right;  // time-compressed, starting at 0
  TimeNs end_ns = 0;
};

// A preset's events from 1 s into its motion, times from 0.
const Workload& Simulated(int sensor) {
  static std::map<int, Workload> cache;
  auto found = cache.find(sensor);
  if (found != cache.end()) return found->second;
  cv::setNumThreads(1);
  sim::SimulationRequest request;
  const Sensor& spec = kSensors[sensor];
  request.preset = spec.preset;
  request.duration_s = 1.0 + spec.seconds;
  request.speed = spec.speed;
  const sim::SimulationWorld world = *sim::BuildSimulationWorld(request);
  sim::StereoEventSimulation simulation(world, 1);
  const TimeNs t0 = world.spline.t_begin_ns() + SecondsToNs(1.0);  // under way
  simulation.Start(t0);
  Workload w;
  const TimeNs span = SecondsToNs(spec.seconds);
  while (simulation.time_ns() < t0 + span)
    simulation.Step(t0 + span, &w.left, &w.right);
  for (auto* stream : {&w.left, &w.right}) {
    for (events::Event& e : *stream)
      e.t_ns -= t0;
  }
  w.end_ns = span;
  w.rectification = geometry::BuildStereoRectification(world.rig);
  w.width = world.rig.width();
  w.height = world.rig.height();
  return cache.emplace(sensor, std::move(w)).first->second;
}

// The benchmark's workload: sensor state.range(0), state.range(1) thousand left events per tick.
const Workload& GetWorkload(const benchmark::State& state) {
  static std::map<std::pair<int, int>, Workload> cache;
  const auto key =
      std::make_pair(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  auto found = cache.find(key);
  if (found != cache.end()) return found->second;
  Workload w = Simulated(key.first);
  const double per_tick = 1e3 * key.second;
  const double scale = per_tick * static_cast<double>(w.end_ns) /
                       (static_cast<double>(w.left.size()) * static_cast<double>(kTick));
  for (auto* stream : {&w.left, &w.right}) {
    for (events::Event& e : *stream)
      e.t_ns = static_cast<TimeNs>(static_cast<double>(e.t_ns) / scale);
  }
  w.end_ns = static_cast<TimeNs>(static_cast<double>(w.end_ns) / scale);
  return cache.emplace(key, std::move(w)).first->second;
}

// Each sensor at its twins' rate and at a higher one.
void Rates(benchmark::internal::Benchmark* b) {
  b->ArgNames({"sensor", "kev_per_tick"});
  for (const auto& [sensor, k] : {std::pair{0, 14}, {0, 50}, {1, 40}, {1, 200}, {2, 100}, {2, 300}})
    b->Args({sensor, k});
}

// Index of the first event after t.
std::size_t After(const std::vector<events::Event>& events, TimeNs t) {
  return static_cast<std::size_t>(
      std::upper_bound(events.begin(), events.end(), t,
                       [](TimeNs v, const events::Event& e) { return v < e.t_ns; }) -
      events.begin());
}

void BM_TimeSurface(benchmark::State& state) {
  const Workload& w = GetWorkload(state);
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
  state.counters["ticks_of_data"] = static_cast<double>(w.end_ns / kTick);
}
BENCHMARK(BM_TimeSurface)->Apply(Rates)->Unit(benchmark::kMillisecond);

// One rectification of a rendered time surface (the left camera's maps).
void BM_Rectify(benchmark::State& state) {
  const Workload& w = GetWorkload(state);
  const events::ImageRectifier rectifier(w.rectification.left);
  events::TimeSurface ts(w.width, w.height, 0);
  (void)ts.Insert(std::span(w.left).subspan(0, After(w.left, 5 * kTick)));
  cv::Mat padded = rectifier.MakePadded(), rectified;
  cv::Mat raw = events::ImageRectifier::PaddedInterior(padded);
  ts.Render(5 * kTick, 30.0, &raw);
  for (auto _ : state) {
    rectifier.RectifyPadded(padded, &rectified);
    benchmark::DoNotOptimize(rectified.data);
  }
}
BENCHMARK(BM_Rectify)->Apply(Rates)->Unit(benchmark::kMillisecond);

void BM_NegativeTsAndGradients(benchmark::State& state) {
  const Workload& w = GetWorkload(state);
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
BENCHMARK(BM_NegativeTsAndGradients)->Apply(Rates)->Unit(benchmark::kMillisecond);

void BM_AaMap(benchmark::State& state) {
  const Workload& w = GetWorkload(state);
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
BENCHMARK(BM_AaMap)->Apply(Rates)->Unit(benchmark::kMillisecond);

void BM_Sampling(benchmark::State& state) {
  const Workload& w = GetWorkload(state);
  events::AdaptiveAccumulator accumulator(w.width, w.height, {});
  events::AaMap map;
  accumulator.Build(w.left, std::min(3 * kTick, w.end_ns), &map);
  events::EdgeSamplingConfig config;  // 2500 points, 8×6
  // The paper's spacing on the DAVIS, the driving preset's on the larger sensors.
  config.min_spacing_px = state.range(0) == 0 ? 0 : 2;
  std::uint64_t seed = 0;
  std::size_t samples = 0;
  for (auto _ : state) {
    const auto s = events::SampleAaMap(map, w.rectification.left, config, ++seed);
    samples = s.size();
    benchmark::DoNotOptimize(s.data());
  }
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_Sampling)->Apply(Rates)->Unit(benchmark::kMillisecond);

void BM_ObservationBothCameras(benchmark::State& state) {
  const Workload& w = GetWorkload(state);
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
BENCHMARK(BM_ObservationBothCameras)->Apply(Rates)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
