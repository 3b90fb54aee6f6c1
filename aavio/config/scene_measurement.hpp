#pragma once
/// The scene's depth measured on a sequence's first moments, for choosing a preset when none is
/// named (ConfigureForRig, ConfigureForSequence). Reads ahead and puts the reader back.

#include <optional>

#include "aavio/common/status.hpp"
#include "aavio/config/config_sources.hpp"
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

/// ConfigureForRig for a sequence: with no preset named, the scene's depth measured on its first
/// moments from begin_ns (MeasureSceneDepth) helps choose one. Returns why that preset ("" when
/// one was named); the reader is back at begin_ns.
Expected<std::string> ConfigureForSequence(io::SequenceReader* reader,
                                           const geometry::StereoRig& rig, TimeNs begin_ns,
                                           TimeNs end_ns, ConfigSources* sources);

}  // namespace aavio::config
