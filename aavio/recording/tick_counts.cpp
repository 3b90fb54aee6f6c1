#include "aavio/recording/tick_counts.hpp"

namespace aavio::recording {

void TickCounts::AddTick(const pipeline::OdometryTick& t) {
  dropped_events_ = t.dropped_events;
  status_counts_[tracking::TrackingStatusName(t.status)]++;
  if (t.status == tracking::TrackingStatus::kLost)
    lost_reasons_[tracking::LostReasonName(t.lost_reason)]++;
  if (t.registration_stop) {
    registration_stops_[tracking::RegistrationStopName(*t.registration_stop)]++;
    ++registered_ticks_;
  }
  stereo_left_out_ += t.stereo_left_out;
  stereo_ticks_ += t.stereo_left_out > 0 ? 1 : 0;
  if (t.status == tracking::TrackingStatus::kImuOnly) {
    // Stretches carried on the IMU alone, [first tick, last tick] in data seconds.
    const double at = NsToSeconds(t.t_ns - begin_ns_);
    if (imu_only_.empty() || !previous_imu_only_) imu_only_.push_back({at, at});
    imu_only_.back()[1] = at;
  }
  previous_imu_only_ = t.status == tracking::TrackingStatus::kImuOnly;
  bootstraps_ += t.bootstrap;
  if (t.bootstrap && !first_bootstrap_ns_) first_bootstrap_ns_ = t.t_ns;
  if (!t.bootstrap_failure.empty()) {
    ++bootstrap_failures_;
    last_bootstrap_failure_ = t.bootstrap_failure;
  }
  skipped_cycles_ += t.mapping_skipped;
  reinitialisations_ += t.reinitialised;
  mapping_cycles_ += t.mapped ? 1 : 0;
}

bool TickCounts::NeverMapped() const {
  if (status_counts_.empty()) return false;
  const auto no_map = status_counts_.find("no_map");
  int ticks = 0;
  for (const auto& [status, n] : status_counts_)
    ticks += n;
  return no_map != status_counts_.end() && no_map->second == ticks;
}

void TickCounts::AddTo(nlohmann::json* summary, std::optional<TimeNs> first_tick_ns) const {
  nlohmann::json& s = *summary;
  s["dropped_events"] = dropped_events_;
  s["status"] = status_counts_;
  s["lost_reasons"] = lost_reasons_;
  s["registration_stops"] = registration_stops_;
  // tracking.stereo_check: the ticks it left map points out on, and how many per registration.
  s["stereo_check"] = {
      {"ticks_leaving_points_out", stereo_ticks_},
      {"points_left_out_per_registration",
       registered_ticks_ > 0 ? static_cast<double>(stereo_left_out_) / registered_ticks_ : 0.0}};
  s["imu_only"] = nlohmann::json::array();
  for (const auto& [from, to] : imu_only_)
    s["imu_only"].push_back({from, to});
  s["bootstraps"] = bootstraps_;
  s["reinitialisations"] = reinitialisations_;
  // Ticks on which a (re-)initialisation found too few points, and the last one's reason.
  s["bootstrap_failures"] = {{"ticks", bootstrap_failures_},
                             {"last_reason", last_bootstrap_failure_}};
  // Data time from the first tick to the first map (null: never mapped; odometry runs only).
  s["first_bootstrap_s"] = nullptr;
  if (first_bootstrap_ns_ && first_tick_ns)
    s["first_bootstrap_s"] = NsToSeconds(*first_bootstrap_ns_ - *first_tick_ns);
  s["mapping_cycles"] = mapping_cycles_;
  s["mapping_cycles_skipped"] = skipped_cycles_;
}

}  // namespace aavio::recording
