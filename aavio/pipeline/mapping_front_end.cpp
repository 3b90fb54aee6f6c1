#include "aavio/pipeline/mapping_front_end.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::pipeline {
MappingFrontEnd::MappingFrontEnd(const geometry::StereoRig& rig, const OdometryConfig& config,
                                 const geometry::PoseBuffer& poses, TimeNs start_ns)
    : config_(config),
      poses_(poses),
      rectification_(geometry::BuildStereoRectification(rig)),
      stereo_(mapping::RectifiedStereo::FromRig(rig)),
      builder_(rectification_, rig.width(), rig.height(), RepresentationConfigOf(config), start_ns),
      mapper_(stereo_, rectification_.left.valid_mask, config.mapping),
      history_(config.mapping.temporal_stereo),
      camera_{rig.width(), rig.height(), rig.focal_px(), rig.cx_left(), rig.cy()},
      decay_(config.time_surface.decay_ms, config.time_surface.adaptive_decay),
      tick_ns_(SecondsToNs(1.0 / config.time_surface.rate_hz)),
      next_tick_ns_(start_ns + tick_ns_),
      ticks_per_cycle_(std::max(
          1, static_cast<int>(std::lround(config.time_surface.rate_hz / config.mapping.rate_hz)))) {
}

Status MappingFrontEnd::Process(std::span<const events::Event> left,
                                std::span<const events::Event> right, TimeNs t_end_ns) {
  AAVIO_RETURN_IF_ERROR(builder_.AddEvents(events::Camera::kLeft, left));
  AAVIO_RETURN_IF_ERROR(builder_.AddEvents(events::Camera::kRight, right));
  while (next_tick_ns_ < t_end_ns) {
    AAVIO_RETURN_IF_ERROR(Tick(next_tick_ns_));
    next_tick_ns_ += tick_ns_;
  }
  return Status::Ok();
}

Status MappingFrontEnd::Tick(TimeNs t_ns) {
  auto obs = std::make_shared<events::Observation>();
  // Between cycles only the left time surface (nothing maps there), as in `Odometry`.
  const bool cycle_tick = (ticks_ + 1) % ticks_per_cycle_ == 0;
  AAVIO_RETURN_IF_ERROR(
      builder_.Build(t_ns, obs.get(),
                     {.right_ts = cycle_tick, .edges = cycle_tick, .decay_ms = decay_.decay_ms()}));
  ++ticks_;
  if (on_tick) on_tick(t_ns, obs->timings);
  Expected<geometry::RigidTransform> pose = poses_.Query(t_ns);
  if (!pose) return Status::Ok();  // no ground truth here: nothing to map with
  const mapping::PosedObservation now{obs, *pose};
  // τ follows the age of the events at the map's edges, as in `Odometry` (there after each
  // tracked tick; here the pose is the ground truth's).
  if (const mapping::LocalMapPtr map = mapper_.local_map(); map && !map->points_world.empty()) {
    const double age_ms = tracking::MedianEdgeAgeMs(map->points_world, *pose, camera_, obs->ts_left,
                                                    decay_.decay_ms());
    if (age_ms >= 0.0) decay_.AddEdgeAge(age_ms);
  }

  if (ticks_ % ticks_per_cycle_ == 0) {
    MappingCycle cycle;
    cycle.t_ns = t_ns;
    cycle.representation = obs->timings;
    cycle.observation = obs;
    bool ran = true;
    if (!mapper_.initialized()) {
      const Status init = mapper_.Initialize(now);
      ran = cycle.bootstrap = init.ok();  // too few points: the next cycle tries again
    } else {
      const mapping::TemporalHistory::Partners partners = history_.PartnersFor(*pose);
      AAVIO_RETURN_IF_ERROR(
          mapper_.Update(now, partners.main_ptr(), &cycle.report, partners.check_ptr()));
    }
    if (cycle.bootstrap || cycle.report.published) cycle.map = mapper_.local_map();
    if (ran && on_cycle) on_cycle(cycle);
  }

  // A cycle's AA map and pose: a later cycle's temporal partner.
  if (cycle_tick) history_.Remember(now);
  return Status::Ok();
}

}  // namespace aavio::pipeline
