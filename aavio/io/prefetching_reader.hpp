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
  /// Starts reading `reader` (already positioned) at once; holds at most `max_packets` packets
  /// ahead, and stops reading ahead once those hold `max_events` events of both cameras (the
  /// memory bound at any event rate; the last packet read may pass it). Once full, it reads
  /// again when half of each has been taken, so the two threads hand over in bursts rather than
  /// waking each other for every packet.
  PrefetchingReader(SequenceReader* reader, std::size_t max_packets,
                    std::size_t max_events = kDefaultMaxEvents);

  /// 4 M events: 64 MB, about half a second of both cameras of a DSEC twin (3.9 Mev/s each).
  static constexpr std::size_t kDefaultMaxEvents = 4'000'000;
  /// Stops the reading thread (a packet being read is finished first).
  ~PrefetchingReader();
  PrefetchingReader(const PrefetchingReader&) = delete;
  PrefetchingReader& operator=(const PrefetchingReader&) = delete;

  /// As SequenceReader::Next: the next packet, false once every stream has ended, or the
  /// reader's error (after which every call returns that error).
  Expected<bool> Next(SensorPacket* packet);

  /// What is read ahead now: packets, and events of both cameras in them.
  struct Buffered {
    std::size_t packets = 0, events = 0;
  };
  Buffered buffered() const;

 private:
  void Run();
  bool Full() const;     // no more may be read ahead
  bool Drained() const;  // once full, reading resumes here

  SequenceReader* reader_;
  std::size_t max_packets_;
  std::size_t max_events_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<SensorPacket> ready_;
  std::size_t ready_events_ = 0;  // of both cameras in ready_
  bool finished_ = false;         // the reader returned false or an error: nothing more comes
  bool stop_ = false;
  bool reader_waits_ = false;  // the reading thread is waiting for room
  Status error_ = Status::Ok();
  std::thread thread_;  // last: starts after every member above exists
};

}  // namespace aavio::io
