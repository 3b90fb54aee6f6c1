#pragma once
/// Internal helpers over the HDF5 C API: owning handles and readable errors. Only the io module
/// includes this header.

#include <hdf5.h>

#include <functional>
#include <string>
#include <utility>

#include "aavio/common/status.hpp"

namespace aavio::io::h5 {

/// Owns an HDF5 identifier and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      Reset();
      id_ = std::exchange(other.id_, -1);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { Reset(); }

  hid_t get() const { return id_; }
  /// Gives up ownership (the caller closes the id).
  hid_t Release() { return std::exchange(id_, -1); }
  bool valid() const { return id_ >= 0; }
  void Reset() {
    if (id_ >= 0 && closer_) closer_(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// Silences HDF5's default printing of its error stack (aavio reports errors itself), on the
/// calling thread (HDF5 keeps the setting per thread). Idempotent and cheap.
void SilenceErrorPrinting();

/// The most specific message on HDF5's current error stack ("" if empty), then clears it.
std::string TakeErrorMessage();

/// Ok if the dataset can be read: every filter of it is available (otherwise an error that names
/// the filter and the Debian package providing it; blosc: hdf5-filter-plugin-blosc-serial), its
/// elements are numbers of 1 to 8 bytes, and a compact dataset stores the bytes its shape needs
/// (a corrupt file otherwise).
Status CheckReadable(hid_t dataset, const std::string& file, const std::string& name);

bool LinkExists(hid_t file, const char* path);

/// Runs `attempt` (opening `path` the way the caller is about to) in a forked child process first:
/// a corrupt file can crash HDF5 1.10 itself (a corrupt local heap makes H5Gopen dereference a
/// failed allocation) before any check of aavio's sees the file, and the crash should end the
/// child, not the caller. Ok when the child ends by itself, whatever `attempt` found (the caller
/// repeats it and reports that); an error naming the file when the child is killed by a signal,
/// exits otherwise than at the end of `attempt`, or runs past `timeout_s`. In a process with
/// other threads, a child asleep for a second without using CPU waits for a lock another thread
/// held when it was forked: it is stopped and forked again (up to 5 times, then an error saying
/// so). Where fork is unavailable or fails, Ok without a probe.
Status SurvivesInChild(const std::string& path, const std::function<void()>& attempt,
                       double timeout_s = 60.0);

}  // namespace aavio::io::h5
