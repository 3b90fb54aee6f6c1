#pragma once
/// summary.json `event_gaps`: the stretches in which a camera sent no events (a dark scene, a
/// covered lens, a camera unplugged, a standstill), per camera, in seconds of data from the
/// run's start. A stretch counts from the last tick that brought events to the first that
/// brings them again, and is listed from 50 ms on. `skipped` lists the gaps in which neither
/// camera gave an event for so long that their ticks were not run, from the last event before to
/// the first after.

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "aavio/common/time.hpp"

namespace aavio::recording {

class EventGaps {
 public:
  explicit EventGaps(TimeNs begin_ns) : begin_ns_(begin_ns), last_events_ns_{begin_ns, begin_ns} {}

  /// A tick's new events per camera (negative: not counted; ignored).
  void Add(TimeNs t_ns, std::int64_t left, std::int64_t right);
  /// A gap whose ticks were not run.
  void AddSkipped(TimeNs from_ns, TimeNs to_ns) {
    skipped_.emplace_back(NsToSeconds(from_ns - begin_ns_), NsToSeconds(to_ns - begin_ns_));
  }
  /// Closes the open stretches at the run's end.
  void Finish(TimeNs end_ns);

  /// {"left": [[from_s, to_s], ...], "right": [...], "skipped": [...]}.
  nlohmann::json Json() const;

 private:
  void Close(int camera, TimeNs t_ns);

  static constexpr TimeNs kMinGapNs = 50 * kNsPerMs;
  TimeNs begin_ns_;
  std::array<TimeNs, 2> last_events_ns_;  // last tick with events, per camera
  std::array<bool, 2> silent_{false, false};
  std::array<std::vector<std::pair<double, double>>, 2> gaps_;
  std::vector<std::pair<double, double>> skipped_;
};

}  // namespace aavio::recording
