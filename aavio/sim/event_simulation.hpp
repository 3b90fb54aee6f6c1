#pragma once
/// Events of both cameras of a simulation world, generated in memory step by step: each step
/// renders both cameras at the next time and turns the change into events (event_generator.hpp).
/// The step adapts so that image motion stays about one pixel per step (angular velocity and
/// speed over the nearest depth in view, plus the fastest moving object's speed), between 50 µs
/// and 5 ms; with flickering lights in the scene, at most a twelfth of their period, so that the
/// linear interpolation between renders follows the flicker's waveform to within ~3 %.

#include <vector>

#include "aavio/events/event.hpp"
#include "aavio/sim/event_generator.hpp"
#include "aavio/sim/renderer.hpp"
#include "aavio/sim/world.hpp"

namespace aavio::sim {

class StereoEventSimulation {
 public:
  /// Renders both cameras at t_begin_ns (the world's spline start if unset) as the reference.
  StereoEventSimulation(const SimulationWorld& world, std::uint64_t seed);
  void Start(TimeNs t_begin_ns);

  /// One step, not past t_end_ns; appends each camera's events (time-ordered) and returns the
  /// new time.
  TimeNs Step(TimeNs t_end_ns, std::vector<events::Event>* left, std::vector<events::Event>* right);

  TimeNs time_ns() const { return t_ns_; }
  const RenderedImage& image(int side) const { return images_[side]; }
  const EventGenerator& generator(int side) const { return generators_[side]; }

 private:
  const SimulationWorld& world_;
  Renderer renderers_[2];
  EventGenerator generators_[2];
  RenderedImage images_[2];
  double f_px_;
  double max_step_s_ = 5e-3;
  double object_speed_mps_ = 0.0;  // the fastest moving object
  TimeNs t_ns_ = 0;
};

}  // namespace aavio::sim
