// `aavio replay`: a sequence played into the live odometry at its own pace, as a driver would
// deliver it, to see whether this machine keeps up with this data and how long a pose takes.
#include <CLI/CLI.hpp>
#include <chrono>
#include <ostream>
#include <thread>

#include "aavio/common/format.hpp"
#include "aavio/config/config_sources.hpp"
#include "aavio/config/scene_measurement.hpp"
#include "aavio/io/prefetching_reader.hpp"
#include "aavio/pipeline/live_odometry.hpp"
#include "cli.hpp"
#include "config_options.hpp"
#include "option_checks.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {
namespace {

struct ReplayOptions {
  std::string sequence, calibration;
  double speed = 1.0;
  double start_s = 0.0, duration_s = 0.0;
  double max_lag_s = 0.05;
  config::ConfigSources config;
};

struct Played {
  TimeNs begin = 0, end = 0;
  std::int64_t events = 0, mapping_cycles = 0;
  double wall_s = 0.0;
};

// Pushes every packet of [begin, end) once the wall clock reaches its end time (divided by
// `speed`): what a driver streaming the cameras and the IMU would do.
Status Play(io::SequenceReader* reader, pipeline::LiveOdometry* live, const ReplayOptions& o,
            Played* played) {
  io::PrefetchingReader prefetching(reader, 256);  // decoding ahead, as a driver's own thread
  const auto wall_start = std::chrono::steady_clock::now();
  io::SensorPacket packet;
  for (;;) {
    Expected<bool> more = prefetching.Next(&packet);
    if (!more) return more.status();
    if (!*more || packet.t_begin_ns >= played->end) break;
    const TimeNs until = std::min(packet.t_end_ns, played->end);
    std::this_thread::sleep_until(wall_start +
                                  std::chrono::nanoseconds(static_cast<std::int64_t>(
                                      static_cast<double>(until - played->begin) / o.speed)));
    AAVIO_RETURN_IF_ERROR(live->PushImu(packet.imu));
    AAVIO_RETURN_IF_ERROR(live->PushEvents(events::Camera::kLeft, packet.left, until));
    AAVIO_RETURN_IF_ERROR(live->PushEvents(events::Camera::kRight, packet.right, until));
    played->events += static_cast<std::int64_t>(packet.left.size() + packet.right.size());
  }
  AAVIO_RETURN_IF_ERROR(live->Finish(played->end));
  played->wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return Status::Ok();
}

int Replay(ReplayOptions& o, Context& ctx) {
  auto fail = [&ctx](const Status& status, int code = kExitError) {
    ctx.err << "aavio replay: error: " << status.message() << "\n";
    return code;
  };
  Expected<OpenedSequence> opened = OpenSequence(o.sequence, o.calibration);
  if (!opened) return fail(opened.status());
  io::SequenceReader* reader = opened->reader.get();
  Played played;
  played.begin = reader->start_ns() + SecondsToNs(o.start_s);
  played.end = o.duration_s > 0.0
                   ? std::min(reader->end_ns(), played.begin + SecondsToNs(o.duration_s))
                   : reader->end_ns();
  if (played.end <= played.begin) {
    return fail(InvalidArgument("--start is past the end of the sequence"), kExitUsage);
  }
  if (o.start_s > 0.0) {
    if (Status s = reader->Seek(played.begin); !s.ok()) return fail(s);
  }
  Expected<std::string> why = config::ConfigureForSequence(reader, opened->calibration.rig,
                                                           played.begin, played.end, &o.config);
  if (!why) return fail(why.status());
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(o.config);
  if (!config) return fail(config.status(), ConfigErrorExitCode(o.config));
  auto live = pipeline::LiveOdometry::Create(opened->calibration.rig, *config, played.begin,
                                             {.real_time = true,
                                              .max_lag_s = o.max_lag_s,
                                              .wait_for_imu = opened->description.imu.has_value()});
  if (!live) return fail(live.status(), kExitUsage);
  (*live)->on_tick = [&played](const pipeline::OdometryTick& tick) {
    if (tick.map) ++played.mapping_cycles;
  };
  if (Status s = Play(reader, live->get(), o, &played); !s.ok()) return fail(s);

  const pipeline::LiveStats stats = (*live)->stats();
  const double data_s = NsToSeconds(played.end - played.begin);
  const std::int64_t due = stats.ticks + stats.skipped_ticks;
  ctx.out << StrFormat(
      "replayed %.2f s of data at %gx in %.2f s (%.1f Mev/s per camera as played, preset %s)\n",
      data_s, o.speed, played.wall_s,
      static_cast<double>(played.events) / 2.0 / data_s * o.speed / 1e6, o.config.preset.c_str());
  ctx.out << StrFormat(
      "ticks: %lld run, %lld shed to keep up (%.1f %% of %lld); mapping cycles: %lld, %lld shed; "
      "the most data waiting at once %.3f s\n",
      static_cast<long long>(stats.ticks), static_cast<long long>(stats.skipped_ticks),
      due > 0 ? 100.0 * static_cast<double>(stats.skipped_ticks) / static_cast<double>(due) : 0.0,
      static_cast<long long>(due), static_cast<long long>(played.mapping_cycles),
      static_cast<long long>(stats.skipped_mapping_cycles), stats.max_backlog_s);
  ctx.out << StrFormat(
      "pose latency (from the push that completed a tick's data to its pose): median %.2f ms, "
      "p99 %.2f ms, max %.2f ms\n",
      stats.latency_median_ms, stats.latency_p99_ms, stats.latency_max_ms);
  return kExitOk;
}

}  // namespace

void RegisterReplay(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<ReplayOptions>();
  CLI::App* sub = app.add_subcommand(
      "replay",
      "Play a sequence into the live odometry at its own pace (real-time mode) and say whether "
      "this machine keeps up: ticks shed, pose latency");
  sub->add_option("sequence", options->sequence, "sequence.yaml, DSEC folder or bag")->required();
  sub->add_option("--calib", options->calibration, "Calibration, if the sequence names none");
  sub->add_option("--speed", options->speed,
                  "Play the data this many times as fast as it was recorded (2: twice the event "
                  "rate per second of wall time)")
      ->check(NumberIn(0.01, 100.0))
      ->capture_default_str();
  sub->add_option("--start", options->start_s, "Seconds to skip")->check(DataSeconds());
  sub->add_option("--duration", options->duration_s, "Seconds to play (default: all)")
      ->check(DataSeconds());
  sub->add_option("--max-lag", options->max_lag_s,
                  "Seconds of data that may wait before ticks are shed to catch up")
      ->check(NumberIn(0.001, 10.0))
      ->capture_default_str();
  AddConfigOptions(*sub, &options->config);
  sub->callback(
      [&ctx, options] { ctx.action = [&ctx, options] { return Replay(*options, ctx); }; });
}

}  // namespace aavio::cli
