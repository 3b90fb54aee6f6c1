#include "aavio/io/prefetching_reader.hpp"

#include <utility>

namespace aavio::io {

namespace {
std::size_t EventsOf(const SensorPacket& packet) {
  return packet.left.size() + packet.right.size();
}
}  // namespace

PrefetchingReader::PrefetchingReader(SequenceReader* reader, std::size_t max_packets,
                                     std::size_t max_events)
    : reader_(reader),
      max_packets_(max_packets > 0 ? max_packets : 1),
      max_events_(max_events),
      thread_([this] { Run(); }) {}

bool PrefetchingReader::Full() const {
  return ready_.size() >= max_packets_ || (!ready_.empty() && ready_events_ >= max_events_);
}

bool PrefetchingReader::Drained() const {
  return ready_.size() <= max_packets_ / 2 && ready_events_ <= max_events_ / 2;
}

PrefetchingReader::Buffered PrefetchingReader::buffered() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {ready_.size(), ready_events_};
}

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
      if (Full()) {
        reader_waits_ = true;
        changed_.wait(lock, [this] { return stop_ || Drained(); });
        reader_waits_ = false;
      }
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
        ready_events_ += EventsOf(packet);
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
  ready_events_ -= EventsOf(*packet);
  const bool wake_reader = reader_waits_ && Drained();
  lock.unlock();
  if (wake_reader) changed_.notify_all();
  return true;
}

}  // namespace aavio::io
