#include "aavio/sim/event_simulation.hpp"

#include <algorithm>
#include <thread>

namespace aavio::sim {
namespace {

/// Smallest depths in view (2nd percentile) bound the optical flow for the adaptive step.
double NearDepth(const std::vector<float>& depth) {
  std::vector<float> sample;
  for (std::size_t i = 0; i < depth.size(); i += 7) {
    if (depth[i] > 0.0f) sample.push_back(depth[i]);
  }
  if (sample.empty()) return 1.0;
  const std::size_t k = sample.size() / 50;
  std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(k), sample.end());
  return std::max(0.05, static_cast<double>(sample[k]));
}

}  // namespace

StereoEventSimulation::StereoEventSimulation(const SimulationWorld& world, std::uint64_t seed)
    : world_(world),
      renderers_{Renderer(world.rig.left()), Renderer(world.rig.right())},
      generators_{
          EventGenerator(world.rig.width(), world.rig.height(), world.preset.events, seed * 2 + 11),
          EventGenerator(world.rig.width(), world.rig.height(), world.preset.events,
                         seed * 2 + 12)},
      f_px_((world.rig.left().intrinsics().fx + world.rig.left().intrinsics().fy) / 2.0) {
  constexpr double kStepsPerFlickerPeriod = 12.0;
  for (const Quad& q : world.scene.quads()) {
    if (q.flicker_hz > 0.0)
      max_step_s_ = std::min(max_step_s_, 1.0 / (kStepsPerFlickerPeriod * q.flicker_hz));
    object_speed_mps_ = std::max(object_speed_mps_, q.velocity_mps.norm());
  }
  Start(world.spline.t_begin_ns());
}

void StereoEventSimulation::Start(TimeNs t_begin_ns) {
  t_ns_ = t_begin_ns;
  for (int side = 0; side < 2; ++side) {
    renderers_[side].Render(world_.scene, world_.T_world_camera(side, t_ns_), t_ns_,
                            &images_[side]);
    generators_[side].Reset(images_[side].intensity, t_ns_);
  }
}

TimeNs StereoEventSimulation::Step(TimeNs t_end_ns, std::vector<events::Event>* left,
                                   std::vector<events::Event>* right) {
  const MotionSpline& spline = world_.spline;
  const double speed_px =
      f_px_ * (spline.AngularVelocity(t_ns_).norm() +
               (spline.LinearVelocity(t_ns_).norm() + object_speed_mps_) /
                   NearDepth(images_[0].depth_m));
  const double dt_s = std::clamp(1.0 / std::max(speed_px, 1e-6), 50e-6, max_step_s_);
  const TimeNs t_next = std::min(t_end_ns, t_ns_ + SecondsToNs(dt_s));
  auto step = [&](int side, std::vector<events::Event>* out) {
    renderers_[side].Render(world_.scene, world_.T_world_camera(side, t_next), t_next,
                            &images_[side]);
    generators_[side].Step(images_[side].intensity, t_next, out);
  };
  std::thread right_thread(step, 1, right);
  step(0, left);
  right_thread.join();
  t_ns_ = t_next;
  return t_ns_;
}

}  // namespace aavio::sim
