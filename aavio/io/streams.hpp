#pragma once
/// Streaming sources of events and IMU samples (one per file / topic) and the time-ordering
/// policy they share. A source never holds more than its read block plus the reorder window.
///
/// Time-order policy: files are expected in time order. An element up to `max_reorder_ns`
/// older than the newest one read so far is put back in place; an element older than that is an
/// error naming the file, the position and the size of the jump.

#include <algorithm>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"
#include "aavio/events/event.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::io {

struct StreamOptions {
  /// Elements may arrive this much out of time order and are reordered (see above).
  TimeNs max_reorder_ns = 10 * kNsPerMs;
  /// Sensor size for the bounds check of events; 0 disables it (size unknown).
  int width = 0;
  int height = 0;
  /// Events read from the file per block (bounds memory: ~16 bytes per event).
  std::size_t block_events = 1 << 16;
};

/// What a source knows without reading it all.
struct StreamInfo {
  std::string description;  ///< e.g. "DSEC events.h5: /path/events.h5"
  std::int64_t count = -1;  ///< elements in the stream, -1 if unknown without a full pass
  TimeNs t_first_ns = 0;    ///< valid when count != 0 (and count known or first read)
  TimeNs t_last_ns = 0;
  int width = 0;  ///< sensor size if the file states it, else 0
  int height = 0;
};

template <typename T>
class Stream {
 public:
  virtual ~Stream() = default;
  virtual const StreamInfo& info() const = 0;
  /// Appends, in time order, every element with t < t_end_ns not returned yet.
  virtual Status ReadUntil(TimeNs t_end_ns, std::vector<T>* out) = 0;
  /// The next ReadUntil starts at the first element with t >= t_ns.
  virtual Status Seek(TimeNs t_ns) = 0;
  /// True once every element has been returned.
  virtual bool AtEnd() const = 0;
};

using EventStream = Stream<events::Event>;
using ImuStream = Stream<imu::ImuSample>;

/// A file format's Stream, its forwarding written once: the format's `Decoder` (declared here,
/// defined in the format's .cpp) holds the `StreamInfo info` and does the work in `ReadUntil`,
/// `Seek` and `AtEnd`. A format's class adds its `Open` and what else it knows of the file; its
/// .cpp defines the destructor and instantiates this class (decoded_stream_impl.hpp).
template <typename T, typename Decoder>
class DecodedStream : public Stream<T> {
 public:
  const StreamInfo& info() const override;
  Status ReadUntil(TimeNs t_end_ns, std::vector<T>* out) override;
  Status Seek(TimeNs t_ns) override;
  bool AtEnd() const override;

 protected:
  explicit DecodedStream(std::unique_ptr<Decoder> decoder);
  ~DecodedStream() override;
  std::unique_ptr<Decoder> decoder_;
};

/// Holds elements read in file order and releases them in time order (the policy above).
template <typename T>
class ReorderBuffer {
 public:
  explicit ReorderBuffer(TimeNs max_reorder_ns) : max_reorder_ns_(max_reorder_ns) {}

  /// Adds an element; `where` describes its position for the error message.
  Status Push(const T& element, std::string_view where_if_error) {
    return PushDescribed(element, [where_if_error] { return where_if_error; });
  }
  /// Push for a reader whose position text costs to build: `where()` (returning the text) is
  /// called only for an element out of time order.
  template <typename Where>
  Status PushDescribed(const T& element, Where&& where) {
    // The common case inline: in time order after everything pushed and released so far.
    if (has_newest_ && element.t_ns >= newest_ns_ && element.t_ns >= released_until_ns_) {
      newest_ns_ = element.t_ns;
      pending_.push_back(element);
      return Status::Ok();
    }
    return PushOutOfOrder(element, where());
  }
  /// Appends the leading elements that are in time order after everything pushed and released so
  /// far, in one copy; returns how many (the caller pushes the next one with Push, which reorders
  /// it or names the error). 0 before the first Push.
  std::size_t AppendInOrder(std::span<const T> elements) {
    if (!has_newest_) return 0;
    TimeNs floor = std::max(newest_ns_, released_until_ns_);
    std::size_t k = 0;
    for (; k < elements.size() && elements[k].t_ns >= floor; ++k)
      floor = elements[k].t_ns;
    if (k == 0) return 0;
    pending_.insert(pending_.end(), elements.begin(),
                    elements.begin() + static_cast<std::ptrdiff_t>(k));
    newest_ns_ = elements[k - 1].t_ns;
    return k;
  }
  /// Everything strictly older than t_end_ns is final once an element at or after
  /// t_end_ns + max_reorder_ns has been pushed (or the source is exhausted).
  bool CanRelease(TimeNs t_end_ns) const {
    return has_newest_ && newest_ns_ >= SaturatingAdd(t_end_ns, max_reorder_ns_);
  }
  /// Moves every held element with t < t_end_ns to `out`, in time order.
  void Release(TimeNs t_end_ns, std::vector<T>* out);
  /// Drops everything and forgets the history (after a seek); elements before `floor_ns` that
  /// arrive later are discarded silently.
  void Reset(TimeNs floor_ns);
  std::size_t size() const { return pending_.size() - begin_; }  ///< held, not yet released

 private:
  Status PushOutOfOrder(const T& element, std::string_view where_if_error);

  TimeNs max_reorder_ns_;
  std::vector<T> pending_;
  std::size_t begin_ = 0;  // pending_[begin_, end) are held
  bool sorted_ = true;
  bool has_newest_ = false;
  TimeNs newest_ns_ = 0;
  TimeNs released_until_ns_ = std::numeric_limits<TimeNs>::min();
  TimeNs floor_ns_ = std::numeric_limits<TimeNs>::min();
};

}  // namespace aavio::io
