#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::pipeline {

Status PipelineConfig::Validate() const {
  FieldChecker check;
  check.NonNegative("random_seed", random_seed)
      .InRange("num_threads", num_threads, 0, 1024)
      .InRange("max_buffered_events", max_buffered_events, 1000, 1'000'000'000)
      .InRange("max_lost_ticks", max_lost_ticks, 1, 100000);
  return check.status();
}

Status OdometryConfig::Validate() const {
  FieldChecker check;
  check.Nested("pipeline", pipeline)
      .Nested("time_surface", time_surface)
      .Nested("adaptive_accumulation", adaptive_accumulation)
      .Nested("edge_sampling", edge_sampling)
      .Nested("mapping", mapping)
      .Nested("tracking", tracking)
      .Nested("imu", imu);
  check
      .Require(mapping.rate_hz <= time_surface.rate_hz, "mapping.rate_hz",
               "= " + FieldChecker::Num(mapping.rate_hz) +
                   " must not exceed time_surface.rate_hz (" +
                   FieldChecker::Num(time_surface.rate_hz) + "): mapping runs on ticks")
      .Require(mapping.max_points <= edge_sampling.num_points ||
                   edge_sampling.mode == events::SamplingMode::kNewestEvents,
               "mapping.max_points",
               "= " + FieldChecker::Num(mapping.max_points) +
                   " exceeds edge_sampling.num_points (" +
                   FieldChecker::Num(edge_sampling.num_points) + "): raise the sampling budget");
  return check.status();
}

events::RepresentationConfig RepresentationConfigOf(const OdometryConfig& config) {
  return {config.time_surface, config.adaptive_accumulation, config.edge_sampling,
          static_cast<std::uint64_t>(config.pipeline.random_seed),
          static_cast<std::size_t>(config.pipeline.max_buffered_events)};
}

}  // namespace aavio::pipeline
