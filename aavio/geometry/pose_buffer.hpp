#pragma once
/// Time-indexed poses with interpolation: the tracker inserts T_world_cam at every tick, the
/// mapper queries it at observation stamps (docs/architecture.md).

#include <deque>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"
#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::geometry {

struct StampedPose {
  TimeNs t_ns = 0;
  RigidTransform T_world_body;
};

class PoseBuffer {
 public:
  /// Keeps poses no older than `history_ns` before the newest one (0 keeps everything).
  explicit PoseBuffer(TimeNs history_ns = 100 * kNsPerS) : history_ns_(history_ns) {}

  /// Appends a pose. Stamps must increase strictly; an older or equal stamp is refused.
  Status Insert(TimeNs t_ns, const RigidTransform& T_world_body);

  /// The pose at t_ns: exact at a stamp, interpolated (slerp + linear) between two stamps.
  /// Outside [oldest, newest] only within `max_extrapolation_ns`, from the nearest two poses;
  /// beyond that, OutOfRange.
  Expected<RigidTransform> Query(TimeNs t_ns, TimeNs max_extrapolation_ns = 0) const;

  bool empty() const { return poses_.empty(); }
  std::size_t size() const { return poses_.size(); }
  const StampedPose& oldest() const { return poses_.front(); }
  const StampedPose& newest() const { return poses_.back(); }
  void Clear() { poses_.clear(); }

 private:
  TimeNs history_ns_;
  std::deque<StampedPose> poses_;
};

}  // namespace aavio::geometry
