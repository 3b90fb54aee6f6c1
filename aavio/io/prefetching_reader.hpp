#pragma once
/// Reads a sequence's packets on a thread of their own, a bounded number ahead of the consumer,
/// so decoding files (HDF5 decompression, bag parsing) overlaps with processing. The packets and
/// their order are exactly those of SequenceReader::Next: prefetching changes when data is read,
/// never what is read.

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "aavio/io/sequence.hpp"

namespace aavio::io {

class PrefetchingReader {
 public:
  /// Starts reading `reader` (already positioned) at once; holds at most `max_packets` ahead.
  PrefetchingReader(SequenceReader* reader, std::size_t max_packets);
  /// Stops the reading thread (a packet being read is finished first).
  ~PrefetchingReader();
  PrefetchingReader(const PrefetchingReader&) = delete;
  PrefetchingReader& operator=(const PrefetchingReader&) = delete;

  /// As SequenceReader::Next: the next packet, false once every stream has ended, or the
  /// reader's error (after which every call returns that error).
  Expected<bool> Next(SensorPacket* packet);

 private:
  void Run();

  SequenceReader* reader_;
  std::size_t max_packets_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<SensorPacket> ready_;
  bool finished_ = false;  // the reader returned false or an error: nothing more comes
  bool stop_ = false;
  Status error_ = Status::Ok();
  std::thread thread_;  // last: starts after every member above exists
};

}  // namespace aavio::io
