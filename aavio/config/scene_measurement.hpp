#pragma once
/// The scene's depth measured on a sequence's first moments, for choosing a preset when none is
/// named (ConfigureForRig). Reads ahead and puts the reader back.

#include <optional>

#include "aavio/common/status.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/pipeline/scene_depth_probe.hpp"

namespace aavio::config {

/// Feeds `reader`'s events from begin_ns into a SceneDepthProbe and measures every
/// SceneDepthProbe::kWindowNs until one measurement has enough edges, for at most kMaxProbeNs
/// (and not past end_ns); the reader is then back at begin_ns. Nothing when the camera shows
/// too few edges all that time (standing still, dark).
inline constexpr TimeNs kMaxProbeNs = 2'000'000'000;
Expected<std::optional<pipeline::SceneDepth>> MeasureSceneDepth(io::SequenceReader* reader,
                                                                const geometry::StereoRig& rig,
                                                                TimeNs begin_ns, TimeNs end_ns);

}  // namespace aavio::config
