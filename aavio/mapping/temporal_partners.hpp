#pragma once
/// Temporal stereo's partners (docs/mapping.md): earlier mapping observations far enough from the
/// current camera for a useful baseline. TemporalHistory keeps the recent ones (their AA maps and
/// poses) on the caller's thread and hands partners out as copies, so that a mapping cycle may
/// run on another thread while later observations are remembered.

#include <optional>
#include <span>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/mapping_config.hpp"
#include "aavio/mapping/posed_observation.hpp"

namespace aavio::mapping {

/// Mapping observations kept for the temporal partner search (1 s at 20 Hz).
inline constexpr int kTemporalHistoryLength = 20;
/// The cross-check partner's distance beyond the first partner, in units of min_translation_m:
/// baselines about 1 : 1.5. At 1 (1 : 2) a mismatch by one period of a periodic texture in the
/// first partner and by two in the second triangulate to the same depth and pass the check (the
/// DSEC twins' paved road, cells of 1.2 m: 8 % of the temporal points off by 30 % or more).
inline constexpr double kCrossCheckSpacing = 0.5;

/// The newest observation of `history` (oldest first) whose camera centre is at least
/// `min_translation_m` from T_world_now's; nullptr if none.
const PosedObservation* FindTemporalPartner(std::span<const PosedObservation> history,
                                            const geometry::RigidTransform& T_world_now,
                                            double min_translation_m);

/// Temporal stereo's partners: `main` as FindTemporalPartner with min_translation_m; `check`
/// (only with cross_check_px > 0) the newest older observation at least kCrossCheckSpacing ×
/// min_translation_m from `main`. Either may be null.
struct TemporalPartners {
  const PosedObservation* main = nullptr;
  const PosedObservation* check = nullptr;
};
TemporalPartners FindTemporalPartners(std::span<const PosedObservation> history,
                                      const geometry::RigidTransform& T_world_now,
                                      const TemporalStereoConfig& config);

/// The newest kTemporalHistoryLength mapping observations (only their AA maps and poses).
class TemporalHistory {
 public:
  explicit TemporalHistory(const TemporalStereoConfig& config) : config_(config) {}

  /// Keeps a mapping observation's AA map and pose as a later temporal partner.
  void Remember(const PosedObservation& observation);
  /// The partners (FindTemporalPartners) for a camera at T_world_now, as copies: they stay
  /// valid while later observations are remembered and after Clear.
  struct Partners {
    std::optional<PosedObservation> main, check;
    const PosedObservation* main_ptr() const { return main ? &*main : nullptr; }
    const PosedObservation* check_ptr() const { return check ? &*check : nullptr; }
  };
  Partners PartnersFor(const geometry::RigidTransform& T_world_now) const;
  void Clear() { history_.clear(); }

 private:
  TemporalStereoConfig config_;
  std::vector<PosedObservation> history_;  // oldest first
};

}  // namespace aavio::mapping
