#include "aavio/geometry/pose_buffer.hpp"

#include <algorithm>

namespace aavio::geometry {

Status PoseBuffer::Insert(TimeNs t_ns, const RigidTransform& T_world_body) {
  if (!poses_.empty() && t_ns <= poses_.back().t_ns) {
    return InvalidArgument("pose stamp " + FormatSecondsNs(t_ns) +
                           " s is not after the newest buffered stamp " +
                           FormatSecondsNs(poses_.back().t_ns) + " s");
  }
  poses_.push_back({t_ns, T_world_body});
  if (history_ns_ > 0) {
    while (poses_.size() > 2 && poses_.front().t_ns < t_ns - history_ns_)
      poses_.pop_front();
  }
  return Status::Ok();
}

Expected<RigidTransform> PoseBuffer::Query(TimeNs t_ns, TimeNs max_extrapolation_ns) const {
  if (poses_.empty()) return OutOfRange("pose buffer is empty");
  const TimeNs oldest_ns = poses_.front().t_ns;
  const TimeNs newest_ns = poses_.back().t_ns;
  if (t_ns < oldest_ns - max_extrapolation_ns || t_ns > newest_ns + max_extrapolation_ns) {
    return OutOfRange("no pose at " + FormatSecondsNs(t_ns) + " s: buffer holds [" +
                      FormatSecondsNs(oldest_ns) + ", " + FormatSecondsNs(newest_ns) + "] s");
  }
  if (poses_.size() == 1) return poses_.front().T_world_body;
  // First pose with stamp >= t; interpolate between it and its predecessor.
  auto after = std::lower_bound(poses_.begin(), poses_.end(), t_ns,
                                [](const StampedPose& p, TimeNs t) { return p.t_ns < t; });
  if (after != poses_.end() && after->t_ns == t_ns) return after->T_world_body;
  if (after == poses_.begin()) ++after;  // extrapolate before the oldest
  if (after == poses_.end()) --after;    // extrapolate past the newest
  const auto before = std::prev(after);
  const double alpha =
      static_cast<double>(t_ns - before->t_ns) / static_cast<double>(after->t_ns - before->t_ns);
  return InterpolatePose(before->T_world_body, after->T_world_body, alpha);
}

}  // namespace aavio::geometry
