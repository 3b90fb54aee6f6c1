#include "aavio/io/prefetching_reader.hpp"

#include <utility>

namespace aavio::io {

PrefetchingReader::PrefetchingReader(SequenceReader* reader, std::size_t max_packets)
    : reader_(reader),
      max_packets_(max_packets > 0 ? max_packets : 1),
      thread_([this] { Run(); }) {}

PrefetchingReader::~PrefetchingReader() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void PrefetchingReader::Run() {
  while (true) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return stop_ || ready_.size() < max_packets_; });
      if (stop_) return;
    }
    SensorPacket packet;
    Expected<bool> more = reader_->Next(&packet);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!more) {
        error_ = more.status();
        finished_ = true;
      } else if (!*more) {
        finished_ = true;
      } else {
        ready_.push_back(std::move(packet));
      }
    }
    changed_.notify_all();
    if (!more || !*more) return;
  }
}

Expected<bool> PrefetchingReader::Next(SensorPacket* packet) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return !ready_.empty() || finished_; });
  if (ready_.empty()) {
    *packet = SensorPacket();
    if (!error_.ok()) return error_;
    return false;
  }
  *packet = std::move(ready_.front());
  ready_.pop_front();
  lock.unlock();
  changed_.notify_all();
  return true;
}

}  // namespace aavio::io
