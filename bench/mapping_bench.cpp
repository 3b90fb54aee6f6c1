// Costs of a mapping cycle on DSEC-like data with 2 threads (issue: event matching ≤ 8 ms, depth
// refinement ≤ 4 ms, fusion ≤ 2 ms, whole cycle ≤ 15 ms at 2.5k samples). The observations are
// real simulator output: the dsec simulation preset's street, 5 s into the drive, with the
// simulator's exact poses; the partners for temporal stereo are the observations ≥ 1 m and ≥ 2 m
// earlier (driving preset, with its cross-check).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <opencv2/core.hpp>

#include "aavio/config/config_sources.hpp"
#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/mapping/mapper.hpp"
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

const Workload& GetWorkload() {
  static const Workload workload = [] {
    Workload w;
    sim::SimulationRequest request;
    request.preset = "dsec";
    request.duration_s = 8.0;
    const sim::SimulationWorld world = *sim::BuildSimulationWorld(request);
    // As `aavio run` configures it: the driving preset, then the sensor's rules.
    const config::ConfigSources sources{.preset = "driving",
                                        .sensor = config::SensorFacts::Of(world.rig)};
    w.config = *config::ResolveOdometryConfig(sources);
    const geometry::StereoRectification rectification =
        geometry::BuildStereoRectification(world.rig);
    w.stereo = mapping::RectifiedStereo::FromRig(world.rig);
    w.valid_mask = rectification.left.valid_mask;
    sim::StereoEventSimulation simulation(world, 1);
    const TimeNs t0 = world.spline.t_begin_ns() + SecondsToNs(5.0);  // at speed
    simulation.Start(t0);
    events::RepresentationConfig rc{w.config.time_surface, w.config.adaptive_accumulation,
                                    w.config.edge_sampling, 1};
    events::RepresentationBuilder builder(rectification, world.rig.width(), world.rig.height(), rc,
                                          t0);
    // 2 s of ticks every 10 ms; every 10th observation is kept (mapping cycles at the preset's 10
    // Hz; the partners ≥ 1 m and ≥ 2 m back exist for the later ones).
    int tick_index = 0;
    for (TimeNs tick = t0 + 10 * kNsPerMs; tick <= t0 + 2000 * kNsPerMs; tick += 10 * kNsPerMs) {
      std::vector<events::Event> left, right;
      while (simulation.time_ns() < tick)
        simulation.Step(tick, &left, &right);
      (void)builder.AddEvents(events::Camera::kLeft, left);
      (void)builder.AddEvents(events::Camera::kRight, right);
      auto obs = std::make_shared<events::Observation>();
      (void)builder.Build(tick, obs.get());
      if (++tick_index % 10 == 0) w.observations.push_back({obs, world.spline.Pose(tick)});
    }
    return w;
  }();
  return workload;
}

void BM_MappingCycle(benchmark::State& state) {
  const Workload& w = GetWorkload();
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
BENCHMARK(BM_MappingCycle)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
