#pragma once
/// The one loop that runs a recorded sequence: its packets of [begin, end), in order, decoded on
/// a thread of their own a bounded number ahead, into the odometry (RunOdometry) or any other
/// consumer (RunSequence: mapping on known poses, a program's own); with the hooks a program needs
/// around it — a stop request (Ctrl-C), progress, and each packet as it is read. `aavio run` and
/// the Python module's `run` both drive the odometry through it, so they give the same trajectory.
///
///   pipeline::Odometry odometry(rig, config, begin_ns);
///   odometry.on_tick = [&](const pipeline::OdometryTick& tick) { poses.push_back(...); };
///   const pipeline::SequenceRun run = pipeline::RunOdometry(*reader, begin_ns, end_ns,
///                                                           &odometry);
///   if (!run.stopped_by.ok()) ...  // an error of the input or of the odometry, at run.reached_ns

#include <cstdint>
#include <functional>

#include "aavio/common/status.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/pipeline/odometry.hpp"

namespace aavio::pipeline {

/// Where a run got to (also passed to the progress hook while it runs).
struct SequenceRun {
  TimeNs begin_ns = 0, end_ns = 0;
  TimeNs reached_ns = 0;         ///< the data time processed up to
  std::int64_t packets = 0;      ///< packets processed
  std::int64_t events = 0;       ///< events of both cameras in them
  std::int64_t imu_samples = 0;  ///< IMU samples read, and the first and last one's stamp
  TimeNs imu_first_ns = 0, imu_last_ns = 0;
  double wall_s = 0.0;       ///< since the loop started
  bool interrupted = false;  ///< the stop hook said to stop
  /// An error that ended the run early: the input's (a corrupt stretch) or the consumer's.
  Status stopped_by = Status::Ok();
};

struct SequenceRunHooks {
  /// Asked before each packet; true ends the run there (what was processed stands).
  std::function<bool()> stop;
  /// Called every `progress_every` packets.
  std::function<void(const SequenceRun&)> on_progress;
  int progress_every = 50;
  /// Each packet as it is read, before it is processed, with the wall time its read took [ms].
  std::function<void(const io::SensorPacket&, double read_ms)> on_packet;
  /// Each packet after it was processed; an error stops the run as the consumer's would (a
  /// recorder that cannot write).
  std::function<Status(const io::SensorPacket&)> after_packet;
  /// Packets decoded ahead of processing (0: read on the caller's thread), within the
  /// prefetching reader's bound of events (io::PrefetchingReader: 4 M, 64 MB). What is read and
  /// in which order does not depend on it.
  int prefetch_packets = 50;
};

/// Hands the packets of [begin_ns, end_ns) to `process` with the time up to which the data is
/// complete (the packet's end, or end_ns) until the sequence ends, the stop hook says so or an
/// error stops it. The reader is where the run starts (seek it to begin_ns first).
using PacketConsumer = std::function<Status(const io::SensorPacket& packet, TimeNs complete_ns)>;
SequenceRun RunSequence(io::SequenceReader& reader, TimeNs begin_ns, TimeNs end_ns,
                        const PacketConsumer& process, const SequenceRunHooks& hooks = {});

/// RunSequence into the odometry: both cameras' events and the IMU samples of every packet, and
/// at the end (also when the stop hook ended it; not after an error) Odometry::Finish for the
/// ticks still waiting for IMU samples.
SequenceRun RunOdometry(io::SequenceReader& reader, TimeNs begin_ns, TimeNs end_ns,
                        Odometry* odometry, const SequenceRunHooks& hooks = {});

}  // namespace aavio::pipeline
