// Streams a recorded sequence through aavio's LiveOdometry as a camera driver would: each
// camera's events and the IMU samples are pushed packet by packet, poses come back through a
// callback. Writes the trajectory (TUM format) and says what the odometry did.
//
//   stream_sequence SEQUENCE [--real-time] [--out trajectory.txt]
//
// SEQUENCE: a sequence.yaml (or a DSEC folder). Without --real-time the poses are those of
// `aavio run SEQUENCE`, bit for bit. With --real-time the packets arrive at the pace of their
// timestamps, as from a live sensor, and the odometry sheds ticks when it falls behind.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "aavio/config/config_sources.hpp"
#include "aavio/config/scene_measurement.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/pipeline/live_odometry.hpp"

namespace {

using namespace aavio;

Status Stream(const std::string& path, bool real_time, const std::string& out) {
  // The sequence, its calibration and a configuration for its rig (as `aavio run` makes it).
  Expected<io::SequenceDescription> sequence = io::DescribeSequence(path);
  if (!sequence) return sequence.status();
  Expected<io::LoadedCalibration> calibration = io::LoadCalibration(sequence->calibration);
  if (!calibration) return calibration.status();
  Expected<std::unique_ptr<io::SequenceReader>> reader =
      io::SequenceReader::Open(*sequence, io::SequenceReaderOptions{});
  if (!reader) return reader.status();
  config::ConfigSources sources;  // no preset named: the rig and the scene's depth choose one
  Expected<std::string> why = config::ConfigureForSequence(
      reader->get(), calibration->rig, (*reader)->start_ns(), (*reader)->end_ns(), &sources);
  if (!why) return why.status();
  std::fprintf(stderr, "preset %s (%s)\n", sources.preset.c_str(), why->c_str());
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(sources);
  if (!config) return config.status();

  Expected<std::unique_ptr<pipeline::LiveOdometry>> live = pipeline::LiveOdometry::Create(
      calibration->rig, *config, (*reader)->start_ns(),
      {.real_time = real_time, .wait_for_imu = (*reader)->imu() != nullptr});
  if (!live) return live.status();
  std::vector<geometry::StampedPose> poses;
  (*live)->on_tick = [&](const pipeline::OdometryTick& tick) {
    poses.push_back({tick.t_ns, tick.T_world_cam});
    if (tick.map) {
      std::fprintf(stderr, "t = %.2f s: new local map, %zu points\n",
                   NsToSeconds(tick.t_ns - (*reader)->start_ns()), tick.map->points_world.size());
    }
  };

  // The driver side: packets of 1 ms, each stream complete up to the packet's end. (To end
  // exactly where `aavio run` ends, at the newest stamp, the last packet is cut there.)
  const TimeNs end_ns = (*reader)->end_ns();
  const auto wall_start = std::chrono::steady_clock::now();
  io::SensorPacket packet;
  for (;;) {
    Expected<bool> more = (*reader)->Next(&packet);
    if (!more) return more.status();
    if (!*more) break;
    if (real_time) {
      std::this_thread::sleep_until(
          wall_start + std::chrono::nanoseconds(packet.t_end_ns - (*reader)->start_ns()));
    }
    AAVIO_RETURN_IF_ERROR((*live)->PushImu(packet.imu));
    AAVIO_RETURN_IF_ERROR((*live)->PushEvents(events::Camera::kLeft, packet.left, packet.t_end_ns));
    AAVIO_RETURN_IF_ERROR(
        (*live)->PushEvents(events::Camera::kRight, packet.right, packet.t_end_ns));
  }
  AAVIO_RETURN_IF_ERROR((*live)->Finish((*reader)->end_ns()));

  const pipeline::LiveStats stats = (*live)->stats();
  std::fprintf(stderr,
               "%lld ticks run, %lld skipped, %lld mapping cycles skipped; events %lld + %lld "
               "pushed, %lld + %lld processed; most data waiting at once %.3f s\n",
               static_cast<long long>(stats.ticks), static_cast<long long>(stats.skipped_ticks),
               static_cast<long long>(stats.skipped_mapping_cycles),
               static_cast<long long>(stats.events_pushed[0]),
               static_cast<long long>(stats.events_pushed[1]),
               static_cast<long long>(stats.events_processed[0]),
               static_cast<long long>(stats.events_processed[1]), stats.max_backlog_s);
  AAVIO_RETURN_IF_ERROR(io::WriteTumTrajectory(out, poses));
  std::fprintf(stderr, "wrote %s (%zu poses)\n", out.c_str(), poses.size());
  return Status::Ok();
}

}  // namespace

int main(int argc, char** argv) {
  std::string sequence, out = "trajectory.txt";
  bool real_time = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--real-time") {
      real_time = true;
    } else if (arg == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else if (sequence.empty() && !arg.empty() && arg[0] != '-') {
      sequence = arg;
    } else {
      std::fprintf(stderr, "usage: stream_sequence SEQUENCE [--real-time] [--out FILE]\n");
      return 2;
    }
  }
  if (sequence.empty()) {
    std::fprintf(stderr, "usage: stream_sequence SEQUENCE [--real-time] [--out FILE]\n");
    return 2;
  }
  const aavio::Status status = Stream(sequence, real_time, out);
  if (!status.ok()) {
    std::fprintf(stderr, "stream_sequence: %s\n", status.message().c_str());
    return 1;
  }
  return 0;
}
