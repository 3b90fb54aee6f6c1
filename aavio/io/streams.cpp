#include "aavio/io/streams.hpp"

#include <algorithm>
#include <cstdint>

#include "aavio/common/format.hpp"

namespace aavio::io {

template <typename T>
Status ReorderBuffer<T>::PushOutOfOrder(const T& element, std::string_view where_if_error) {
  if (element.t_ns < floor_ns_) return Status::Ok();
  // How far behind the newest, without overflow: a corrupt file's stamps may span all of int64,
  // and the unsigned difference of two int64 is exact when the first is the larger.
  const bool behind = has_newest_ && element.t_ns < newest_ns_;
  const std::uint64_t back_ns =
      behind ? static_cast<std::uint64_t>(newest_ns_) - static_cast<std::uint64_t>(element.t_ns)
             : 0;
  if (element.t_ns < released_until_ns_ ||
      (behind && back_ns > static_cast<std::uint64_t>(max_reorder_ns_))) {
    return InvalidArgument(std::string(where_if_error) + ": timestamp " +
                           FormatSecondsNs(element.t_ns) + " s goes back " +
                           StrFormat("%.3f ms", static_cast<double>(back_ns) * 1e-6) +
                           " behind the newest one, more than the reorder window of " +
                           StrFormat("%.3f ms", NsToMs(max_reorder_ns_)) +
                           "; sort the file by time (or raise the reorder window)");
  }
  if (has_newest_ && element.t_ns < newest_ns_) sorted_ = false;
  if (!has_newest_ || element.t_ns > newest_ns_) newest_ns_ = element.t_ns;
  has_newest_ = true;
  pending_.push_back(element);
  return Status::Ok();
}

template <typename T>
void ReorderBuffer<T>::Release(TimeNs t_end_ns, std::vector<T>* out) {
  if (!sorted_) {
    std::stable_sort(pending_.begin() + static_cast<std::ptrdiff_t>(begin_), pending_.end(),
                     [](const T& a, const T& b) { return a.t_ns < b.t_ns; });
    sorted_ = true;
  }
  // Held elements are sorted: the first at or after t_end_ns by bisection.
  const std::size_t end = static_cast<std::size_t>(
      std::partition_point(pending_.begin() + static_cast<std::ptrdiff_t>(begin_), pending_.end(),
                           [t_end_ns](const T& x) { return x.t_ns < t_end_ns; }) -
      pending_.begin());
  out->insert(out->end(), pending_.begin() + static_cast<std::ptrdiff_t>(begin_),
              pending_.begin() + static_cast<std::ptrdiff_t>(end));
  begin_ = end;
  released_until_ns_ = std::max(released_until_ns_, t_end_ns);
  // Compact once the released prefix dominates, keeping memory at the window size.
  if (begin_ > 4096 && begin_ * 2 > pending_.size()) {
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(begin_));
    begin_ = 0;
  }
}

template <typename T>
void ReorderBuffer<T>::Reset(TimeNs floor_ns) {
  pending_.clear();
  begin_ = 0;
  sorted_ = true;
  has_newest_ = false;
  released_until_ns_ = std::numeric_limits<TimeNs>::min();
  floor_ns_ = floor_ns;
}

template class ReorderBuffer<events::Event>;
template class ReorderBuffer<imu::ImuSample>;

}  // namespace aavio::io
