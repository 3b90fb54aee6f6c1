#include "aavio/recording/event_gaps.hpp"

namespace aavio::recording {

void EventGaps::Add(TimeNs t_ns, std::int64_t left, std::int64_t right) {
  const std::int64_t counts[2] = {left, right};
  for (int camera = 0; camera < 2; ++camera) {
    if (counts[camera] < 0) continue;
    if (counts[camera] == 0) {
      silent_[camera] = true;
    } else {
      if (silent_[camera]) Close(camera, t_ns);
      last_events_ns_[camera] = t_ns;
    }
  }
}

void EventGaps::Finish(TimeNs end_ns) {
  for (int camera = 0; camera < 2; ++camera) {
    if (silent_[camera]) Close(camera, end_ns);
  }
}

void EventGaps::Close(int camera, TimeNs t_ns) {
  silent_[camera] = false;
  if (t_ns - last_events_ns_[camera] < kMinGapNs) return;
  gaps_[camera].emplace_back(NsToSeconds(last_events_ns_[camera] - begin_ns_),
                             NsToSeconds(t_ns - begin_ns_));
}

nlohmann::json EventGaps::Json() const {
  nlohmann::json j = nlohmann::json::object();
  j["left"] = nlohmann::json::array();
  j["right"] = nlohmann::json::array();
  for (int camera = 0; camera < 2; ++camera) {
    for (const auto& [from, to] : gaps_[camera])
      j[camera == 0 ? "left" : "right"].push_back({from, to});
  }
  j["skipped"] = nlohmann::json::array();
  for (const auto& [from, to] : skipped_)
    j["skipped"].push_back({from, to});
  return j;
}

}  // namespace aavio::recording
