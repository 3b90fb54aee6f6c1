#include "aavio/mapping/temporal_partners.hpp"

namespace aavio::mapping {

const PosedObservation* FindTemporalPartner(std::span<const PosedObservation> history,
                                            const geometry::RigidTransform& T_world_now,
                                            double min_translation_m) {
  for (auto it = history.rbegin(); it != history.rend(); ++it) {
    if ((it->T_world_obs.t - T_world_now.t).norm() >= min_translation_m) return &*it;
  }
  return nullptr;
}

TemporalPartners FindTemporalPartners(std::span<const PosedObservation> history,
                                      const geometry::RigidTransform& T_world_now,
                                      const TemporalStereoConfig& config) {
  TemporalPartners partners;
  partners.main = FindTemporalPartner(history, T_world_now, config.min_translation_m);
  if (partners.main == nullptr || config.cross_check_px <= 0.0) return partners;
  const auto older = history.first(static_cast<std::size_t>(partners.main - history.data()));
  partners.check = FindTemporalPartner(older, partners.main->T_world_obs,
                                       kCrossCheckSpacing * config.min_translation_m);
  return partners;
}

void TemporalHistory::Remember(const PosedObservation& observation) {
  auto light = std::make_shared<events::Observation>();
  light->t_ns = observation.obs->t_ns;
  light->aa_map = observation.obs->aa_map;
  history_.push_back({std::move(light), observation.T_world_obs});
  if (static_cast<int>(history_.size()) > kTemporalHistoryLength) history_.erase(history_.begin());
}

TemporalHistory::Partners TemporalHistory::PartnersFor(
    const geometry::RigidTransform& T_world_now) const {
  const TemporalPartners found = FindTemporalPartners(history_, T_world_now, config_);
  Partners partners;
  if (found.main) partners.main = *found.main;
  if (found.check) partners.check = *found.check;
  return partners;
}

}  // namespace aavio::mapping
