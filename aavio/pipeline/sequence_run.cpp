#include "aavio/pipeline/sequence_run.hpp"

#include <algorithm>
#include <chrono>
#include <optional>

#include "aavio/io/prefetching_reader.hpp"

namespace aavio::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

SequenceRun RunSequence(io::SequenceReader& reader, TimeNs begin_ns, TimeNs end_ns,
                        const PacketConsumer& process, const SequenceRunHooks& hooks) {
  std::optional<io::PrefetchingReader> prefetching;
  if (hooks.prefetch_packets > 0)
    prefetching.emplace(&reader, static_cast<std::size_t>(hooks.prefetch_packets));
  const auto wall_start = Clock::now();
  SequenceRun run;
  run.begin_ns = begin_ns;
  run.end_ns = end_ns;
  run.reached_ns = begin_ns;
  io::SensorPacket packet;
  for (;;) {
    if (hooks.stop && hooks.stop()) {
      run.interrupted = true;
      break;
    }
    const auto read_start = Clock::now();
    Expected<bool> more = prefetching ? prefetching->Next(&packet) : reader.Next(&packet);
    if (!more) {
      run.stopped_by = more.status();
      break;
    }
    if (!*more || packet.t_begin_ns >= end_ns) break;
    if (hooks.on_packet) hooks.on_packet(packet, 1e3 * SecondsSince(read_start));
    if (!packet.imu.empty()) {
      if (run.imu_samples == 0) run.imu_first_ns = packet.imu.front().t_ns;
      run.imu_samples += static_cast<std::int64_t>(packet.imu.size());
      run.imu_last_ns = packet.imu.back().t_ns;
    }
    const TimeNs complete_ns = std::min(packet.t_end_ns, end_ns);
    run.stopped_by = process(packet, complete_ns);
    if (run.stopped_by.ok() && hooks.after_packet) run.stopped_by = hooks.after_packet(packet);
    if (!run.stopped_by.ok()) break;
    run.reached_ns = complete_ns;
    run.events += static_cast<std::int64_t>(packet.left.size() + packet.right.size());
    ++run.packets;
    if (hooks.on_progress && hooks.progress_every > 0 &&
        (run.packets - 1) % hooks.progress_every == 0) {
      run.wall_s = SecondsSince(wall_start);
      hooks.on_progress(run);
    }
  }
  run.wall_s = SecondsSince(wall_start);
  return run;
}

SequenceRun RunOdometry(io::SequenceReader& reader, TimeNs begin_ns, TimeNs end_ns,
                        Odometry* odometry, const SequenceRunHooks& hooks) {
  SequenceRun run = RunSequence(
      reader, begin_ns, end_ns,
      [odometry](const io::SensorPacket& packet, TimeNs complete_ns) {
        return odometry->Process(packet.left, packet.right, packet.imu, complete_ns);
      },
      hooks);
  // The ticks still waiting for IMU samples past the last packet (a positive time offset); also
  // when stopped on request: the data processed until then is all in.
  if (run.stopped_by.ok()) run.stopped_by = odometry->Finish();
  return run;
}

}  // namespace aavio::pipeline
