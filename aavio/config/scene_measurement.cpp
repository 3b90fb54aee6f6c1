#include "aavio/config/scene_measurement.hpp"

#include <algorithm>

namespace aavio::config {

Expected<std::optional<pipeline::SceneDepth>> MeasureSceneDepth(io::SequenceReader* reader,
                                                                const geometry::StereoRig& rig,
                                                                TimeNs begin_ns, TimeNs end_ns) {
  pipeline::SceneDepthProbe probe(rig, begin_ns);
  const TimeNs stop_ns = std::min(end_ns, begin_ns + kMaxProbeNs);
  std::optional<pipeline::SceneDepth> found;
  TimeNs next_ns = begin_ns + pipeline::SceneDepthProbe::kWindowNs;
  io::SensorPacket packet;
  while (!found && next_ns <= stop_ns) {
    Expected<bool> more = reader->Next(&packet);
    if (!more) return more.status();
    if (*more) {
      AAVIO_RETURN_IF_ERROR(probe.AddEvents(events::Camera::kLeft, packet.left));
      AAVIO_RETURN_IF_ERROR(probe.AddEvents(events::Camera::kRight, packet.right));
    }
    // Measure at every window's end the packets have passed (all of them once data ends): a
    // packet holds its events before t_end_ns, so one at t_end_ns itself is in the next.
    while (!found && next_ns <= stop_ns && (!*more || packet.t_end_ns > next_ns)) {
      Expected<std::optional<pipeline::SceneDepth>> depth = probe.Measure(next_ns);
      if (!depth) return depth.status();
      found = *depth;
      next_ns += pipeline::SceneDepthProbe::kWindowNs;
    }
    if (!*more) break;
  }
  AAVIO_RETURN_IF_ERROR(reader->Seek(begin_ns));
  return found;
}

Expected<std::string> ConfigureForSequence(io::SequenceReader* reader,
                                           const geometry::StereoRig& rig, TimeNs begin_ns,
                                           TimeNs end_ns, ConfigSources* sources) {
  std::optional<pipeline::SceneDepth> scene;
  if (sources->preset.empty()) {
    Expected<std::optional<pipeline::SceneDepth>> measured =
        MeasureSceneDepth(reader, rig, begin_ns, end_ns);
    if (!measured) return measured.status();
    scene = *measured;
  }
  return ConfigureForRig(rig, sources, scene);
}

}  // namespace aavio::config
