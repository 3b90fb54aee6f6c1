#pragma once
/// Edge pixels for mapping (docs/representations.md): a budget of pixels from the AA map, spread
/// over the grid of blocks and favouring high counts — or, as the baseline, ESVO's newest events.
/// Samples are taken in raw coordinates and rectified once through the event LUT; pixels whose
/// rectified position is outside the image or the valid mask are never offered.

#include <cstdint>
#include <span>
#include <vector>

#include "aavio/events/adaptive_accumulation.hpp"
#include "aavio/events/events_config.hpp"
#include "aavio/geometry/rectification.hpp"

namespace aavio::events {

struct EdgeSample {
  std::uint16_t x = 0, y = 0;  ///< raw pixel
  float u = 0.0f, v = 0.0f;    ///< rectified position
  std::uint16_t count = 0;     ///< AA count (1 for ESVO's events)
};

/// Per-block quotas (docs/representations.md, [ESVO2]): ¾ of M in proportion to the blocks'
/// candidates n_i, each block capped at ½·n_i, and what is left of M shared evenly among the blocks
/// with room, repeatedly, until M is met or every block is at its cap.
std::vector<int> BlockQuotas(const std::vector<int>& candidates, const EdgeSamplingConfig& config);

/// Samples the AA map: per block its quota of highest-count pixels, ties broken at random from
/// `seed` (same seed and map → same samples).
std::vector<EdgeSample> SampleAaMap(const AaMap& map, const geometry::RectificationMaps& maps,
                                    const EdgeSamplingConfig& config, std::uint64_t seed);

/// The window ESVO's selection looks back over [ms].
inline constexpr double kNewestEventsWindowMs = 10.0;

/// ESVO's selection: the newest events of (t − kNewestEventsWindowMs, t], at most M, one sample
/// each.
std::vector<EdgeSample> SelectNewestEvents(std::span<const Event> events, TimeNs t_ns,
                                           const geometry::RectificationMaps& maps,
                                           const EdgeSamplingConfig& config);

/// ESVO's selection with its budget set to `count` (at least 1): the baseline at the same point
/// count as another selection, for comparisons.
std::vector<EdgeSample> SelectNewestEventsAtCount(std::span<const Event> events, TimeNs t_ns,
                                                  const geometry::RectificationMaps& maps,
                                                  EdgeSamplingConfig config, std::size_t count);

}  // namespace aavio::events
