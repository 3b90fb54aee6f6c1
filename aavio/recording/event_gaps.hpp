#pragma once
/// summary.json `event_gaps`: the stretches in which a camera sent no events (a dark scene, a
/// covered lens, a camera unplugged, a standstill), per camera, in seconds of data from the
/// run's start. A stretch counts from the last tick that brought events to the first that
/// brings them again, and is listed from 50 ms on.

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
  /// Closes the open stretches at the run's end.
  void Finish(TimeNs end_ns);

  /// {"left": [[from_s, to_s], ...], "right": [...]}.
  nlohmann::json Json() const;

 private:
  void Close(int camera, TimeNs t_ns);

  static constexpr TimeNs kMinGapNs = 50 * kNsPerMs;
  TimeNs begin_ns_;
  std::array<TimeNs, 2> last_events_ns_;  // last tick with events, per camera
  std::array<bool, 2> silent_{false, false};
  std::array<std::vector<std::pair<double, double>>, 2> gaps_;
};

}  // namespace aavio::recording
