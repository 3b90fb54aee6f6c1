// Costs of a mapping cycle with 2 threads, and of its temporal stereo on one, per sensor size:
// the observations are real simulator output — each simulation preset's scene (rpg 240×180 with
// the indoor preset, dsec 640×480 with the driving preset, tum_vie 1280×720 with the indoor
// preset; the sensor's rules on top, as `aavio run` resolves them) some seconds into its motion,
// with the simulator's exact poses and the temporal partners the preset finds (the driving
// preset's with their cross-check).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aavio/config/config_sources.hpp"
#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/mapping/mapper.hpp"
#include "aavio/mapping/temporal_partners.hpp"
#include "aavio/mapping/temporal_stereo.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/sim/event_simulation.hpp"

namespace {

using namespace aavio;

struct Workload {
  pipeline::OdometryConfig config;
  mapping::RectifiedStereo stereo;
  cv::Mat valid_mask;
  std::vector<mapping::PosedObservation> observations;  // every 10 ms
};

// Benchmark argument: the preset, its odometry preset, where the mapping starts and how long it
// runs (observations every 10 ms; one in ten goes to the mapper, as at the presets' 10 Hz).
struct Sensor {
  const char* preset;
  const char* odometry_preset;
  double start_s, seconds;
};
constexpr Sensor kSensors[] = {
    {"rpg", "indoor", 2.0, 2.0}, {"dsec", "driving", 5.0, 2.0}, {"tum_vie", "indoor", 2.0, 0.6}};

const Workload& GetWorkload(int sensor) {
  static std::map<int, Workload> cache;
  auto found = cache.find(sensor);
  if (found != cache.end()) return found->second;
  const Sensor& spec = kSensors[sensor];
  Workload w;
  sim::SimulationRequest request;
  request.preset = spec.preset;
  request.duration_s = spec.start_s + spec.seconds + 1.0;
  const sim::SimulationWorld world = *sim::BuildSimulationWorld(request);
  // As `aavio run` configures it: the preset, then the sensor's rules.
  const config::ConfigSources sources{.preset = spec.odometry_preset,
                                      .sensor = config::SensorFacts::Of(world.rig)};
  w.config = *config::ResolveOdometryConfig(sources);
  const geometry::StereoRectification rectification = geometry::BuildStereoRectification(world.rig);
  w.stereo = mapping::RectifiedStereo::FromRig(world.rig);
  w.valid_mask = rectification.left.valid_mask;
  sim::StereoEventSimulation simulation(world, 1);
  const TimeNs t0 = world.spline.t_begin_ns() + SecondsToNs(spec.start_s);  // under way
  simulation.Start(t0);
  events::RepresentationConfig rc{w.config.time_surface, w.config.adaptive_accumulation,
                                  w.config.edge_sampling, 1};
  events::RepresentationBuilder builder(rectification, world.rig.width(), world.rig.height(), rc,
                                        t0);
  int tick_index = 0;
  const TimeNs end = t0 + SecondsToNs(spec.seconds);
  for (TimeNs tick = t0 + 10 * kNsPerMs; tick <= end; tick += 10 * kNsPerMs) {
    std::vector<events::Event> left, right;
    while (simulation.time_ns() < tick)
      simulation.Step(tick, &left, &right);
    (void)builder.AddEvents(events::Camera::kLeft, left);
    (void)builder.AddEvents(events::Camera::kRight, right);
    auto obs = std::make_shared<events::Observation>();
    (void)builder.Build(tick, obs.get());
    if (++tick_index % 10 == 0) w.observations.push_back({obs, world.spline.Pose(tick)});
  }
  return cache.emplace(sensor, std::move(w)).first->second;
}

void BM_MappingCycle(benchmark::State& state) {
  const Workload& w = GetWorkload(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  cv::setNumThreads(1);
  mapping::Mapper mapper(w.stereo, w.valid_mask, w.config.mapping);
  const std::size_t n = w.observations.size();
  // Cycles from the first observation with both temporal partners on, round and round.
  std::size_t first = 1;
  while (first + 1 < n && mapping::FindTemporalPartners(std::span(w.observations.data(), first),
                                                        w.observations[first].T_world_obs,
                                                        w.config.mapping.temporal_stereo)
                                  .check == nullptr) {
    ++first;
  }
  (void)mapper.Initialize(w.observations[first - 1]);
  double matching = 0, refinement = 0, fusion = 0, samples = 0, points = 0, temporal = 0,
         with_partner = 0, candidates = 0;
  std::size_t k = first;
  for (auto _ : state) {
    const mapping::PosedObservation& now = w.observations[k];
    const mapping::TemporalPartners partners = mapping::FindTemporalPartners(
        std::span(w.observations.data(), k), now.T_world_obs, w.config.mapping.temporal_stereo);
    mapping::MappingCycleReport report;
    (void)mapper.Update(now, partners.main, &report, partners.check);
    matching += report.matching_ms, refinement += report.refinement_ms, fusion += report.fusion_ms;
    samples += report.samples, points += report.map_points;
    temporal += report.temporal_matches;
    with_partner += report.has_partner ? 1 : 0, candidates += report.temporal_candidates;
    k = k + 1 < n ? k + 1 : first;
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["matching_ms"] = matching / iterations;
  state.counters["refinement_ms"] = refinement / iterations;
  state.counters["fusion_ms"] = fusion / iterations;
  state.counters["samples"] = samples / iterations;
  state.counters["map_points"] = points / iterations;
  state.counters["temporal_matches"] = temporal / iterations;
  state.counters["with_partner"] = with_partner / iterations;
  state.counters["temporal_candidates"] = candidates / iterations;
}
BENCHMARK(BM_MappingCycle)
    ->ArgName("sensor")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

// Temporal stereo alone, on one thread: every edge sample of a cycle searched along its
// epipolar segment in the partner's AA map and, with the driving preset, the check partner's
// (the cycle's own split sends only the near-horizontal ones there).
void BM_TemporalStereo(benchmark::State& state) {
  const Workload& w = GetWorkload(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const mapping::TemporalStereoConfig& config = w.config.mapping.temporal_stereo;
  // The first observation with both partners, else the first with one.
  std::size_t k = 0;
  mapping::TemporalPartners partners;
  for (std::size_t i = 1; i < w.observations.size(); ++i) {
    const mapping::TemporalPartners found = mapping::FindTemporalPartners(
        std::span(w.observations.data(), i), w.observations[i].T_world_obs, config);
    if (found.main == nullptr || (k > 0 && found.check == nullptr)) continue;
    if (k == 0 || partners.check == nullptr) k = i, partners = found;
    if (found.check != nullptr) break;
  }
  if (k == 0) {
    state.SkipWithError("no observation has a temporal partner");
    return;
  }
  const mapping::PosedObservation& now = w.observations[k];
  // As the mapper prepares them (smoothed AA maps as floats).
  auto as_float = [&](const cv::Mat& aa) {
    cv::Mat source = aa, out;
    if (config.smooth_aa)
      cv::GaussianBlur(aa, source, cv::Size(5, 5), 0.0, 0.0, cv::BORDER_REFLECT_101);
    source.convertTo(out, CV_32F);
    return out;
  };
  const cv::Mat aa_now = as_float(now.obs->aa_map), aa_past = as_float(partners.main->obs->aa_map);
  const geometry::RigidTransform T_past_now =
      partners.main->T_world_obs.Inverse() * now.T_world_obs;
  mapping::TemporalStereoInput input{aa_now, aa_past, T_past_now};
  cv::Mat aa_check;
  geometry::RigidTransform T_check_now;
  if (partners.check != nullptr) {
    aa_check = as_float(partners.check->obs->aa_map);
    T_check_now = partners.check->T_world_obs.Inverse() * now.T_world_obs;
    input.aa_check = &aa_check;
    input.T_check_now = &T_check_now;
  }
  std::vector<Eigen::Vector2f> points;
  for (const events::EdgeSample& s : now.obs->samples)
    points.emplace_back(s.u, s.v);
  std::size_t matches = 0;
  for (auto _ : state) {
    const std::vector<mapping::Match> found = mapping::MatchTemporal(
        input, points, w.stereo, config, w.config.mapping.static_stereo.zncc_threshold,
        w.config.mapping.inv_depth_range());
    matches = found.size();
    benchmark::DoNotOptimize(found.data());
  }
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["matches"] = static_cast<double>(matches);
  state.counters["check"] = partners.check != nullptr ? 1 : 0;
}
BENCHMARK(BM_TemporalStereo)
    ->ArgName("sensor")
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
