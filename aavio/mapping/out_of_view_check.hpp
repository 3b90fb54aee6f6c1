#pragma once
/// Static matches the right camera cannot have made (aavio). A left pixel whose surface is so
/// near that its disparity exceeds the pixel's distance to the left border has its true match
/// outside the right image; the row search, cut at the border, then settles on another edge at
/// a smaller disparity (on the DSEC twins 8 % of the map points on 04e, 28 % off on average).
/// The previous map, moved into the current frame, tells where such near surfaces are: a match
/// within `radius_px` of one, and more than 20 % farther than it, is dropped.

#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/local_map.hpp"
#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::mapping {

/// Removes from `matches` (static ones, rectified left pixels) those the rule above rejects.
/// `patch_half_width`: the static patch's half width (the right patch must fit in the image).
void DropOutOfViewMatches(const LocalMap& previous, const geometry::RigidTransform& T_world_now,
                          const RectifiedStereo& stereo, int patch_half_width, int radius_px,
                          std::vector<Match>* matches);

}  // namespace aavio::mapping
