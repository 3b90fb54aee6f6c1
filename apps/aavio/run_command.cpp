// `aavio run`: the full odometry, and two modes that isolate one half of it: mapping only
// (`--gt-poses`: the sequence's ground-truth poses drive mapping, and the maps are scored
// against its ground-truth depth, docs/evaluation.md) and tracking only (`--gt-map`, against maps
// of the true depth, ground_truth_maps.cpp). Every mode reads the sequence in one loop and leaves
// its outputs through one recording::RunRecorder.
#include <tbb/global_control.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/config/scene_measurement.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/io/trajectory_writing.hpp"
#include "aavio/pipeline/mapping_front_end.hpp"
#include "aavio/pipeline/odometry.hpp"
#include "aavio/pipeline/sequence_run.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "cli.hpp"
#include "config_options.hpp"
#include "ground_truth_maps.hpp"
#include "option_checks.hpp"
#include "run_printing.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {
namespace {

// How far before its first pose the ground truth still gives the start pose (extrapolated): a
// recorded path's stamps have sub-microsecond digits where events are stamped in microseconds, so
// the first event can precede the first pose by a fraction of a microsecond.
constexpr TimeNs kGroundTruthStartToleranceNs = 1'000'000;

struct RunOptions {
  std::string sequence, calibration, out_dir;
  bool overwrite = false;
  bool gt_poses = false;
  bool gt_map = false;
  bool esvo = false;
  bool real_time = false;
  bool quiet = false;
  double start_s = 0.0, duration_s = 0.0;
  int repeat = 1;
  std::string format = "tum", poses_at;
  std::string world = "first_camera";  ///< or "gravity"
  config::ConfigSources config;
};

// Ctrl-C (or SIGTERM) during a run: stop after the current packet and write what is done. A
// second one ends the program at once (the default action is back).
std::atomic<bool> g_interrupted{false};
extern "C" void OnInterrupt(int signal_number) {
  g_interrupted.store(true);
  std::signal(signal_number, SIG_DFL);
}

// The configuration is for this sequence's rig: its sensor's settings, and the preset it and
// its first moments from `begin` suggest when none is named (every mode of `aavio run`).
Status ConfigureForSequence(OpenedSequence& opened, TimeNs begin, TimeNs end, RunOptions* options,
                            Context& ctx) {
  if (!options->quiet) {
    for (const std::string& warning : opened.calibration.warnings)
      ctx.err << "warning: " << warning << "\n";
  }
  Expected<std::string> why = config::ConfigureForSequence(
      opened.reader.get(), opened.calibration.rig, begin, end, &options->config);
  if (!why) return why.status();
  if (!why->empty() && !options->quiet) {
    ctx.err << "aavio run: no --preset given; using '" << options->config.preset << "' (" << *why
            << ")\n";
  }
  return Status::Ok();
}

const char* ModeName(const RunOptions& o) {
  if (o.gt_poses) return "mapping_only_gt_poses";
  if (o.gt_map) return "tracking_only_gt_map";
  return o.esvo ? "esvo" : "full";
}

// The sequence's ground truth, for the recorder to score against. The modes on ground truth
// need it; the full odometry evaluates where the sequence has a ground-truth trajectory.
Status LoadGroundTruth(const OpenedSequence& s, bool required,
                       std::optional<recording::RunGroundTruth>* truth,
                       std::vector<geometry::StampedPose>* gt_poses) {
  const io::SequenceDescription& d = s.description;
  if (!required && !d.gt_trajectory) return Status::Ok();
  if (!d.gt_trajectory) {
    return InvalidArgument(d.origin +
                           ": --gt-poses and --gt-map need ground truth, and the sequence names "
                           "no ground_truth.trajectory");
  }
  Expected<recording::RunGroundTruth> of = recording::RunGroundTruth::Of(d, s.calibration.rig);
  if (!of) return of.status();
  Expected<std::vector<geometry::StampedPose>> poses = of->ReadPoses();
  if (!poses) return poses.status();
  *truth = std::move(*of);
  *gt_poses = std::move(*poses);
  return Status::Ok();
}

// What `aavio run` adds around the library's loop: Ctrl-C stops it, each packet is counted in the
// recorder, and on a terminal the progress is shown.
pipeline::SequenceRunHooks RunHooks(recording::RunRecorder* recorder, bool progress, Context& ctx) {
  pipeline::SequenceRunHooks hooks;
  hooks.stop = [] { return g_interrupted.load(); };
  hooks.on_packet = [recorder](const io::SensorPacket& packet, double read_ms) {
    recorder->AddPacket(packet.left.size() + packet.right.size(), read_ms);
    recorder->AddImu(packet.imu);
  };
  if (progress) {
    hooks.on_progress = [recorder, &ctx](const pipeline::SequenceRun& run) {
      const double done = NsToSeconds(run.reached_ns - run.begin_ns);
      const std::map<std::string, int>& counts = recorder->status_counts();
      auto count = [&](const char* key) { return counts.count(key) ? counts.at(key) : 0; };
      ctx.err << StrFormat("\r%.1f / %.1f s of data, %.2fx real time, tracking ok %d, lost %d   ",
                           done, NsToSeconds(run.end_ns - run.begin_ns),
                           run.wall_s > 0 ? done / run.wall_s : 0.0, count("ok"), count("lost"))
              << std::flush;
    };
  }
  return hooks;
}

// Ctrl-C and SIGTERM set g_interrupted while a run is on; the handlers before are back after.
class InterruptHandlers {
 public:
  InterruptHandlers()
      : previous_int_(std::signal(SIGINT, OnInterrupt)),
        previous_term_(std::signal(SIGTERM, OnInterrupt)) {
    g_interrupted.store(false);
  }
  ~InterruptHandlers() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;

 private:
  using Handler = void (*)(int);
  Handler previous_int_, previous_term_;
};

// What a run needs besides the sequence, prepared before the output folder is touched (so that
// an error in the input leaves no half-written folder).
struct RunSetup {
  TimeNs begin = 0, end = 0;
  io::TrajectoryFormat format = io::TrajectoryFormat::kTum;
  std::vector<TimeNs> poses_at;
  pipeline::OdometryConfig config;
  std::optional<recording::RunGroundTruth> truth;
  std::vector<geometry::StampedPose> gt_list;
  geometry::PoseBuffer gt_poses{0};
  std::optional<GroundTruthMaps> gt_maps;  // --gt-map
  geometry::RigidTransform start_pose;     // --gt-map: the ground truth's at `begin`
};

// The span to run, the output formats and the configuration; `exit_code` says whether an error
// is a wrong argument.
Status PrepareRun(RunOptions* options, OpenedSequence& opened, RunSetup* setup, Context& ctx,
                  int* exit_code) {
  io::SequenceReader* reader = opened.reader.get();
  setup->begin = reader->start_ns() + SecondsToNs(options->start_s);
  setup->end = options->duration_s > 0.0 ? setup->begin + SecondsToNs(options->duration_s)
                                         : reader->end_ns();
  Expected<io::TrajectoryFormat> format = io::WritableTrajectoryFormat(options->format);
  if (!format) {
    *exit_code = kExitUsage;
    return format.status().WithContext("--format");
  }
  setup->format = *format;
  if (!options->poses_at.empty()) {
    Expected<std::vector<TimeNs>> stamps = io::ReadStamps(options->poses_at);
    if (!stamps) return stamps.status().WithContext("--poses-at");
    setup->poses_at = std::move(*stamps);
  }
  if (options->start_s > 0.0) AAVIO_RETURN_IF_ERROR(reader->Seek(setup->begin));
  AAVIO_RETURN_IF_ERROR(ConfigureForSequence(opened, setup->begin, setup->end, options, ctx));
  // The ESVO-like mode is the shipped overlay configs/overlays/esvo.yaml (the embedded one, even
  // if a file named "esvo" is here), after the user's files; --set still applies.
  if (options->esvo) options->config.overlays.push_back("esvo");
  if (options->real_time) options->config.overrides.push_back("pipeline.real_time=true");
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(options->config);
  if (!config) {
    *exit_code = ConfigErrorExitCode(options->config);
    return config.status();
  }
  setup->config = std::move(*config);
  return Status::Ok();
}

// The ground truth the run is scored against, and what the modes on ground truth follow.
Status PrepareGroundTruth(const RunOptions& options, const OpenedSequence& opened,
                          RunSetup* setup) {
  // A repeated sequence jumps back at each seam: its ground truth no longer applies.
  if (options.repeat == 1) {
    AAVIO_RETURN_IF_ERROR(LoadGroundTruth(opened, options.gt_poses || options.gt_map, &setup->truth,
                                          &setup->gt_list));
  }
  for (const geometry::StampedPose& p : setup->gt_list)
    AAVIO_RETURN_IF_ERROR(setup->gt_poses.Insert(p.t_ns, p.T_world_body));
  if (!options.gt_map) return Status::Ok();
  Expected<GroundTruthMaps> maps = GroundTruthMaps::Create(opened, setup->gt_poses);
  if (!maps) return maps.status();
  setup->gt_maps.emplace(std::move(*maps));
  Expected<geometry::RigidTransform> at_start =
      setup->gt_poses.Query(setup->begin, kGroundTruthStartToleranceNs);
  if (!at_start) return at_start.status().WithContext("ground truth at the start");
  setup->start_pose = *at_start;
  return Status::Ok();
}

Expected<std::unique_ptr<recording::RunRecorder>> OpenRecorder(const RunOptions& options,
                                                               const OpenedSequence& opened,
                                                               RunSetup* setup) {
  recording::RunRecorderOptions recorder;
  recorder.out_dir = options.out_dir;
  recorder.overwrite = options.overwrite;
  recorder.mode = ModeName(options);
  // Absolute, so that `aavio eval --run` and `aavio report` find it from any folder.
  recorder.sequence =
      std::filesystem::absolute(opened.description.origin).lexically_normal().string();
  recorder.calibration =
      std::filesystem::absolute(opened.description.calibration).lexically_normal().string();
  recorder.version = VersionString();
  recorder.begin_ns = setup->begin;
  recorder.format = setup->format;
  recorder.poses_at = std::move(setup->poses_at);
  using World = recording::RunRecorderOptions::World;
  recorder.world = options.gt_poses || options.gt_map ? World::kGroundTruth
                   : options.world == "gravity"       ? World::kGravity
                                                      : World::kFirstCamera;
  recorder.config_yaml = io::FormatConfigYaml(
      FlattenConfig(setup->config), "aavio effective configuration (" + VersionString() +
                                        ")\nfrom: " + config::DescribeSources(options.config) +
                                        (options.esvo ? " (ESVO-like mode, --esvo)" : ""));
  Expected<std::unique_ptr<recording::RunRecorder>> opened_recorder =
      recording::RunRecorder::Open(recorder, opened.calibration.rig, setup->config);
  if (!opened_recorder) return opened_recorder.status();
  if (setup->truth)
    AAVIO_RETURN_IF_ERROR((*opened_recorder)->SetGroundTruth(*setup->truth, setup->gt_list));
  return opened_recorder;
}

// The mode's front end, fed the sequence by the library's loop, each tick or mapping cycle into
// the recorder. An error of the recorder (a full disk) stops the run as an input error would.
pipeline::SequenceRun Drive(const RunOptions& options, OpenedSequence& opened, RunSetup& setup,
                            recording::RunRecorder& recorder, Context& ctx) {
  const geometry::StereoRig& rig = opened.calibration.rig;
  Status callback_status = Status::Ok();
  auto keep = [&](const Status& s) {
    if (callback_status.ok()) callback_status = s;
  };
  std::optional<pipeline::Odometry> odometry;
  std::optional<pipeline::MappingFrontEnd> mapping;
  if (options.gt_poses) {
    mapping.emplace(rig, setup.config, setup.gt_poses, setup.begin);
    mapping->on_tick = [&](TimeNs t_ns, const events::RepresentationTimings& t) {
      recorder.AddMappingTick(t_ns, t);
    };
    mapping->on_cycle = [&](const pipeline::MappingCycle& c) { keep(recorder.AddMappingCycle(c)); };
  } else {
    odometry.emplace(rig, setup.config, setup.begin, setup.start_pose,
                     /*run_mapping=*/!options.gt_map);
    odometry->on_tick = [&](const pipeline::OdometryTick& t) { keep(recorder.AddTick(t)); };
    if (setup.gt_maps) {
      odometry->before_tick = [&](const events::Observation& obs) {
        Expected<std::shared_ptr<tracking::TrackingMap>> map = setup.gt_maps->MapFor(obs);
        if (!map) return keep(map.status());
        if (*map) odometry->SetTrackingMap(std::move(*map));
      };
    }
  }
  const bool progress = !options.quiet && isatty(STDERR_FILENO);
  pipeline::SequenceRunHooks hooks = RunHooks(&recorder, progress, ctx);
  hooks.after_packet = [&](const io::SensorPacket& packet) {
    if (odometry) {
      recorder.AddStage("event_insertion", odometry->last_insertion_ms(),
                        static_cast<double>(packet.left.size() + packet.right.size()));
    }
    return callback_status;
  };
  pipeline::SequenceRun fed;
  {
    InterruptHandlers interrupts;
    if (odometry) {
      fed = pipeline::RunOdometry(*opened.reader, setup.begin, setup.end, &*odometry, hooks);
    } else {
      fed = pipeline::RunSequence(
          *opened.reader, setup.begin, setup.end,
          [&](const io::SensorPacket& packet, TimeNs complete_ns) {
            return mapping->Process(packet.left, packet.right, complete_ns);
          },
          hooks);
    }
  }
  if (progress) ctx.err << "\r" << std::string(90, ' ') << "\r";
  if (fed.stopped_by.ok()) fed.stopped_by = callback_status;  // met by Odometry::Finish's ticks
  return fed;  // a mapping cycle still running finishes as the odometry goes
}

// Writes the run's summary and says how it went. Stopped by an error (a full disk, a corrupt
// stretch of the input), what was done until then is written all the same, and the error is
// the command's result.
Expected<bool> Conclude(const RunOptions& options, const OpenedSequence& opened,
                        const RunSetup& setup, const pipeline::SequenceRun& fed,
                        recording::RunRecorder& recorder, Context& ctx) {
  nlohmann::json extra = nlohmann::json::object();
  // Legal input the run could not use well: kept in summary.json, and said at the end.
  std::vector<std::string> warnings = opened.calibration.warnings;
  const std::string imu_warning =
      io::ImuStreamWarning(opened.description, fed.imu_samples, fed.imu_first_ns, fed.imu_last_ns,
                           setup.config.time_surface.rate_hz);
  if (!imu_warning.empty()) {
    warnings.push_back(imu_warning);
    if (!options.quiet) ctx.err << "warning: " << imu_warning << "\n";
  }
  extra["warnings"] = warnings;
  if (!fed.stopped_by.ok()) extra["stopped_by"] = fed.stopped_by.message();
  if (options.repeat > 1) extra["repeat"] = options.repeat;
  RunPrintout printout{.mapping_only = options.gt_poses,
                       .out_dir = options.out_dir,
                       .format = setup.format,
                       .imu_mode = EnumName(setup.config.imu.mode)};
  if (options.gt_map) {
    printout.tracking_error = RelativeErrorOver100Ms(recorder.trajectory(), setup.gt_poses);
    extra["imu_mode"] = printout.imu_mode;
    extra["rpe_100ms"] = {{"rotation_deg_rmse", printout.tracking_error->rotation_deg_rmse},
                          {"translation_m_rmse", printout.tracking_error->translation_m_rmse},
                          {"pairs", printout.tracking_error->pairs}};
  }
  Expected<recording::RunRecord> record = recorder.Finish(fed.interrupted, fed.reached_ns, extra);
  if (!fed.stopped_by.ok()) {
    return Status(
        fed.stopped_by.code(),
        StrFormat("%s\nthe run stopped there, after %.2f s of data; %s %s",
                  fed.stopped_by.message().c_str(), NsToSeconds(fed.reached_ns - setup.begin),
                  options.out_dir.c_str(),
                  record ? "holds what was done until then"
                         : ("holds what could be written of it (" + record.status().message() + ")")
                               .c_str()));
  }
  if (!record) return record.status();
  // No score where one was due is an error (an interrupted run's result is the interruption).
  if (!record->accuracy_error.ok() && !fed.interrupted) {
    return Status(record->accuracy_error.code(),
                  record->accuracy_error.message() + "\n" + options.out_dir +
                      " holds the run's outputs; its summary.json says why it has no accuracy");
  }
  if (recorder.trajectory().empty() && !fed.interrupted && !options.gt_poses) {
    return FailedPrecondition(StrFormat(
        "no pose was estimated: the %.3f s of data read hold no tick (one every %.1f ms, "
        "time_surface.rate_hz): check --start and --duration against the sequence's span "
        "(`aavio info %s`)",
        record->data_s, 1e3 / setup.config.time_surface.rate_hz, options.sequence.c_str()));
  }
  if (const std::string never = recorder.NeverMappedReason(); !never.empty() && !fed.interrupted) {
    return FailedPrecondition(never + "\n" + options.out_dir + " holds the run's outputs");
  }
  PrintRun(*record, printout, ctx);
  return fed.interrupted;
}

// Returns whether the run was interrupted (its outputs hold what was done); on an error,
// `exit_code` says whether it is a wrong argument.
Expected<bool> Run(RunOptions options, Context& ctx, int* exit_code) {
  if (options.repeat > 1 && (options.gt_poses || options.gt_map)) {
    *exit_code = kExitUsage;
    return InvalidArgument(
        "--repeat is for the full odometry; --gt-poses and --gt-map follow "
        "the ground truth, which a repeated sequence does not have");
  }
  Expected<OpenedSequence> opened =
      OpenSequence(options.sequence, options.calibration, options.repeat);
  if (!opened) return opened.status();
  RunSetup setup;
  AAVIO_RETURN_IF_ERROR(PrepareRun(&options, *opened, &setup, ctx, exit_code));
  // Worker threads of the parallel stages (TBB) and of OpenCV; 0 = all cores.
  cv::setNumThreads(setup.config.pipeline.num_threads);
  std::optional<tbb::global_control> workers;
  if (setup.config.pipeline.num_threads > 0) {
    workers.emplace(tbb::global_control::max_allowed_parallelism,
                    static_cast<std::size_t>(setup.config.pipeline.num_threads));
  }
  AAVIO_RETURN_IF_ERROR(PrepareGroundTruth(options, *opened, &setup));
  Expected<std::unique_ptr<recording::RunRecorder>> recorder =
      OpenRecorder(options, *opened, &setup);
  if (!recorder) return recorder.status();
  const pipeline::SequenceRun fed = Drive(options, *opened, setup, **recorder, ctx);
  return Conclude(options, *opened, setup, fed, **recorder, ctx);
}

}  // namespace

void RegisterRun(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand(
      "run",
      "Run the odometry on a sequence (or mapping only: --gt-poses, tracking only: --gt-map)");
  sub->add_option("sequence", options->sequence, "sequence.yaml, DSEC folder or bag")->required();
  sub->add_option("--out", options->out_dir, "Output folder")->required();
  sub->add_flag("--overwrite", options->overwrite,
                "Replace an earlier run in --out (else that is an error)");
  sub->add_option("--calib", options->calibration, "Calibration, if the sequence names none");
  sub->add_flag("--gt-poses", options->gt_poses,
                "Mapping only, with the sequence's ground-truth poses instead of tracking");
  sub->add_flag("--esvo", options->esvo,
                "ESVO-like mode: newest-event selection of 10k points (1k under 0.1 Mpx), "
                "static stereo only, no IMU prior, zero-motion prediction");
  sub->add_flag("--real-time", options->real_time,
                "Maps reach tracking as soon as they are done and cycles are skipped while one "
                "runs (pipeline.real_time): for live input, not bit-reproducible");
  sub->add_flag("--gt-map", options->gt_map,
                "Tracking only, against maps built from the sequence's ground-truth depth");
  sub->add_option("--start", options->start_s, "Seconds to skip")->check(DataSeconds());
  sub->add_option("--duration", options->duration_s, "Seconds to process (default: all)")
      ->check(DataSeconds());
  sub->add_option("--repeat", options->repeat,
                  "Read the sequence N times back to back, its clock shifted each time: a long "
                  "run from a short sequence, for memory and speed over time (no accuracy)")
      ->check(NumberIn(1, 100000));
  sub->add_option("--format", options->format,
                  "Also write the trajectory as trajectory_FORMAT.txt: tum, tum_ns (nanosecond "
                  "stamps), kitti (+ _times.txt), euroc (.csv, world-frame velocity) or evslam "
                  "(camera-frame velocity)")
      ->capture_default_str();
  sub->add_option("--poses-at", options->poses_at,
                  "A file of stamps (first column; s or ns): the --format trajectory at these, "
                  "interpolated (e.g. EvSLAM's reference times)");
  sub->add_option("--world", options->world,
                  "The world of the trajectory and map.ply: first_camera (the first camera's "
                  "frame, as ESVO) or gravity (that frame turned z-up along the gravity the run "
                  "measured; needs an IMU with its extrinsic and 2 s of data)")
      ->check(CLI::IsMember({"first_camera", "gravity"}))
      ->capture_default_str();
  sub->add_flag("--quiet", options->quiet, "No progress output");
  AddConfigOptions(*sub, &options->config);
  sub->callback([&ctx, options] {
    ctx.action = [&ctx, options] {
      if ((options->gt_poses || options->gt_map) && options->world == "gravity") {
        ctx.err << "aavio run: --world gravity is for the odometry; with --gt-poses or --gt-map "
                   "the run's world is the ground truth's\n";
        return static_cast<int>(kExitUsage);
      }
      if (options->gt_poses && options->gt_map) {
        ctx.err << "aavio run: --gt-poses (mapping only) and --gt-map (tracking only) exclude "
                   "each other; give neither for the full odometry\n";
        return static_cast<int>(kExitUsage);
      }
      int exit_code = kExitError;
      const Expected<bool> interrupted = Run(*options, ctx, &exit_code);
      if (!interrupted) {
        ctx.err << "aavio run: error: " << interrupted.status().message() << "\n";
        return exit_code;
      }
      return static_cast<int>(*interrupted ? kExitInterrupted : kExitOk);
    };
  });
}

}  // namespace aavio::cli
