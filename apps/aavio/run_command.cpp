// `aavio run`: the full odometry (odometry_run.cpp), and two modes that isolate one half of it:
// mapping only (`--gt-poses`: the sequence's ground-truth poses drive mapping, and the maps are
// scored against its ground-truth depth, design.md §6) and tracking only (`--gt-map`,
// track_gt_map.cpp).
#include <tbb/global_control.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/eval/depth_error.hpp"
#include "aavio/eval/sample_ceiling.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/mapping/mapper.hpp"
#include "aavio/pipeline/mapping_front_end.hpp"
#include "aavio/pipeline/stage_timings.hpp"
#include "cli.hpp"
#include "config_resolution.hpp"
#include "mapping_counts.hpp"
#include "odometry_run.hpp"
#include "run_evaluation.hpp"
#include "sequence_opening.hpp"
#include "track_gt_map.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;

struct RunOptions {
  std::string sequence, calibration, out_dir;
  bool gt_poses = false;
  bool gt_map = false;
  bool esvo = false;
  bool real_time = false;
  bool quiet = false;
  double start_s = 0.0, duration_s = 0.0;
  ConfigSources config;
};

Expected<geometry::PoseBuffer> GroundTruthPoses(const io::SequenceDescription& d) {
  if (!d.gt_trajectory) {
    return InvalidArgument(d.origin +
                           ": --gt-poses needs ground truth, and the sequence names no "
                           "ground_truth.trajectory");
  }
  if (d.gt_trajectory->format != io::SourceFormat::kText) {
    return InvalidArgument(d.gt_trajectory->path +
                           ": --gt-poses reads TUM text trajectories (convert a bag's poses with "
                           "`aavio convert --to txt`)");
  }
  Expected<std::vector<geometry::StampedPose>> poses = io::ReadTumTrajectory(d.gt_trajectory->path);
  if (!poses) return poses.status();
  geometry::PoseBuffer buffer(0);
  for (const geometry::StampedPose& p : *poses)
    AAVIO_RETURN_IF_ERROR(buffer.Insert(p.t_ns, p.T_world_body));
  return buffer;
}

std::atomic<bool> g_interrupted{false};  // Ctrl-C during a run: stop and write what is done
extern "C" void OnInterrupt(int) {
  g_interrupted.store(true);
}

// No preset named: the one for this camera's resolution (every mode of `aavio run`).
void ChoosePreset(const OpenedSequence& opened, RunOptions* options, Context& ctx) {
  if (!options->config.preset.empty()) return;
  options->config.preset = opened.calibration.rig.width() <= 400 ? "rpg" : "dsec";
  if (!options->quiet) {
    ctx.err << "aavio run: no --preset given; using '" << options->config.preset << "' for "
            << opened.calibration.rig.width() << "x" << opened.calibration.rig.height()
            << " cameras\n";
  }
}

Status RunFull(RunOptions options, OpenedSequence& opened, Context& ctx) {
  // The ESVO-like mode is the shipped overlay configs/overlays/esvo.yaml (the embedded one, even
  // if a file named "esvo" is here), after the user's files; --set still applies.
  if (options.esvo) options.config.overlays.push_back("esvo");
  if (options.real_time) options.config.overrides.push_back("pipeline.real_time=true");
  Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(options.config);
  if (!config) return config.status();
  io::SequenceReader* reader = opened.reader.get();
  const TimeNs begin = reader->start_ns() + SecondsToNs(options.start_s);
  const TimeNs end =
      options.duration_s > 0.0 ? begin + SecondsToNs(options.duration_s) : reader->end_ns();
  if (options.start_s > 0.0) AAVIO_RETURN_IF_ERROR(reader->Seek(begin));
  // Worker threads of the parallel stages (TBB) and of OpenCV; 0 = all cores.
  cv::setNumThreads(config->pipeline.num_threads);
  std::optional<tbb::global_control> workers;
  if (config->pipeline.num_threads > 0) {
    workers.emplace(tbb::global_control::max_allowed_parallelism,
                    static_cast<std::size_t>(config->pipeline.num_threads));
  }
  OdometryRunRequest request;
  request.sequence = &opened;
  request.config = &*config;
  request.config_origin =
      DescribeSources(options.config) + (options.esvo ? " (ESVO-like mode, --esvo)" : "");
  request.mode = options.esvo ? "esvo" : "full";
  request.begin_ns = begin;
  request.end_ns = end;
  request.out_dir = options.out_dir;
  request.progress = !options.quiet && isatty(STDERR_FILENO);
  g_interrupted.store(false);
  request.interrupted = &g_interrupted;
  auto previous = std::signal(SIGINT, OnInterrupt);
  Expected<OdometryRunResult> result = RunOdometry(request, ctx);
  std::signal(SIGINT, previous);
  return result.status();
}

Status Run(RunOptions options, Context& ctx) {
  const auto wall_start = std::chrono::steady_clock::now();
  Expected<OpenedSequence> opened = OpenSequence(options.sequence, options.calibration);
  if (!opened) return opened.status();
  ChoosePreset(*opened, &options, ctx);
  if (!options.gt_poses && !options.gt_map) return RunFull(options, *opened, ctx);
  Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(options.config);
  if (!config) return config.status();
  const io::SequenceDescription* d = &opened->description;
  const geometry::StereoRig& rig = opened->calibration.rig;
  io::SequenceReader* reader = opened->reader.get();
  Expected<geometry::PoseBuffer> poses = GroundTruthPoses(*d);
  if (!poses) return poses.status();
  const TimeNs begin = reader->start_ns() + SecondsToNs(options.start_s);
  const TimeNs end =
      options.duration_s > 0.0 ? begin + SecondsToNs(options.duration_s) : reader->end_ns();
  if (options.start_s > 0.0) AAVIO_RETURN_IF_ERROR(reader->Seek(begin));
  if (options.gt_map) {
    return RunTrackingOnGtMap({&*opened, &*poses, &*config, begin, end, options.out_dir}, ctx);
  }

  std::vector<io::GtDepthEntry> gt_depth;
  if (!d->gt_depth.empty()) {
    Expected<std::vector<io::GtDepthEntry>> index = io::ReadGtDepthIndex(d->gt_depth);
    if (!index) return index.status();
    gt_depth = std::move(*index);
  }
  const mapping::RectifiedStereo stereo = mapping::RectifiedStereo::FromRig(rig);
  eval::DepthErrorAccumulator depth_all(
      {stereo.width, stereo.height, stereo.f, stereo.cx_left, stereo.cy, stereo.fb()});
  // What the map could cover at best: its cycles' samples at their true depth.
  eval::SampleCeiling ceiling({stereo.width, stereo.height, stereo.f, stereo.cx_left, stereo.cy},
                              1.0 / config->mapping.inv_depth_max,
                              1.0 / config->mapping.inv_depth_min,
                              config->mapping.fusion.radius == 0 ? 2 : 3);
  pipeline::StageTimings timings;
  Status cycle_status = Status::Ok();
  std::int64_t cycles = 0, bootstraps = 0, depth_maps = 0;
  std::size_t map_points_sum = 0;
  MappingCounts counts;

  pipeline::MappingFrontEnd front_end(rig, *config, *poses, begin);
  front_end.on_tick = [&](const events::RepresentationTimings& t) {
    timings.Add("time_surface", t.time_surface_ms);
    if (t.edges) {  // mapping ticks only
      timings.Add("aa_map", t.aa_ms);
      timings.Add("sampling", t.sampling_ms);
    }
  };
  front_end.on_cycle = [&](const pipeline::MappingCycle& cycle) {
    ++cycles;
    bootstraps += cycle.bootstrap ? 1 : 0;
    if (cycle.map && cycle.map->confirmed) {
      ++depth_maps;
      map_points_sum += cycle.map->points.size();
    }
    if (!cycle.bootstrap) {
      const mapping::MappingCycleReport& r = cycle.report;
      timings.Add("matching", r.matching_ms, r.static_candidates + r.temporal_candidates);
      timings.Add("depth_refinement", r.refinement_ms, r.static_matches + r.temporal_matches);
      timings.Add("fusion", r.fusion_ms, r.map_points);
      timings.Add("mapping_total", r.total_ms, r.samples);
      counts.Add(r);
    }
    // Only cycles whose samples went into the fusion count for the ceiling.
    const bool fused = cycle.bootstrap || cycle.report.fused_cycles > 0;
    if (!fused || gt_depth.empty() || !cycle_status.ok()) return;
    // The ground-truth depth frame nearest in time (within 25 ms), seen from its own pose.
    auto it = std::lower_bound(gt_depth.begin(), gt_depth.end(), cycle.t_ns,
                               [](const io::GtDepthEntry& e, TimeNs t) { return e.t_ns < t; });
    const io::GtDepthEntry* best = nullptr;
    for (auto c : {it, it == gt_depth.begin() ? it : it - 1}) {
      if (c == gt_depth.end()) continue;
      if (!best || std::llabs(c->t_ns - cycle.t_ns) < std::llabs(best->t_ns - cycle.t_ns))
        best = &*c;
    }
    if (!best || std::llabs(best->t_ns - cycle.t_ns) > 25 * kNsPerMs) return;
    Expected<geometry::RigidTransform> pose = poses->Query(best->t_ns);
    if (!pose) return;
    Expected<io::GtDepthFrame> frame =
        io::LoadGtDepthFrame(d->gt_depth, *best, stereo.fb(), stereo.cx_left - stereo.cx_right);
    if (!frame) {
      cycle_status = frame.status();
      return;
    }
    // The samples as a mapping cycle takes them (an SGM bootstrap uses all of the observation's;
    // its one cycle is counted with these). Read on the ground-truth frame nearest the cycle.
    if (cycle.bootstrap) ceiling.Clear();
    std::vector<Eigen::Vector2f> samples;
    for (const events::EdgeSample& e :
         mapping::MappingSamples(*cycle.observation, stereo, config->mapping))
      samples.emplace_back(e.u, e.v);
    ceiling.AddCycle(samples, frame->depth_m, *pose);
    if (!cycle.map || !cycle.map->confirmed) return;
    depth_all.Add(cycle.map->points_world, frame->depth_m, frame->edges, *pose);
    ceiling.Score(cycle.bootstrap ? 1 : static_cast<std::size_t>(cycle.report.fused_cycles),
                  frame->depth_m, frame->edges, *pose);
  };

  const bool progress = !options.quiet && isatty(STDERR_FILENO);
  std::int64_t events = 0;
  io::SensorPacket packet;
  while (true) {
    Expected<bool> more = reader->Next(&packet);
    if (!more) return more.status();
    if (!*more || packet.t_begin_ns >= end) break;
    events += static_cast<std::int64_t>(packet.left.size() + packet.right.size());
    AAVIO_RETURN_IF_ERROR(front_end.Process(packet.left, packet.right, packet.t_end_ns));
    AAVIO_RETURN_IF_ERROR(cycle_status);
    if (progress && front_end.ticks() % 100 == 0) {
      ctx.err << StrFormat("\rmapping %.1f s", NsToSeconds(packet.t_end_ns - begin)) << std::flush;
    }
  }
  if (progress) ctx.err << "\r";
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double data_s = NsToSeconds(std::min(end, reader->end_ns()) - begin);

  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) return IoError(options.out_dir + ": cannot create the folder (" + ec.message() + ")");
  AAVIO_RETURN_IF_ERROR(
      io::WriteTextFile((fs::path(options.out_dir) / "config.yaml").string(),
                        io::FormatConfigYaml(FlattenConfig(*config),
                                             "aavio effective configuration (" + VersionString() +
                                                 ")\nfrom: " + DescribeSources(options.config))));
  nlohmann::json summary;
  summary["mode"] = "mapping_only_gt_poses";
  summary["data_duration_s"] = data_s;
  summary["wall_s"] = wall_s;
  summary["real_time_factor"] = wall_s > 0.0 ? data_s / wall_s : 0.0;
  summary["events"] = events;
  summary["mapping_cycles"] = cycles;
  summary["bootstraps"] = bootstraps;
  summary["depth_maps"] = depth_maps;
  summary["mean_map_points"] =
      depth_maps > 0 ? static_cast<double>(map_points_sum) / depth_maps : 0.0;
  summary["mapping_per_cycle"] = counts.PerCycleJson(cycles);
  for (const auto& [stage, s] : timings.Summary()) {
    summary["stages"][stage] = {{"median_ms", s.median_ms},
                                {"p95_ms", s.p95_ms},
                                {"calls", s.calls},
                                {"median_items", s.median_items},
                                {"total_s", s.total_s}};
  }
  const eval::DepthErrorSummary depth = depth_all.Summary();
  if (!gt_depth.empty()) {
    summary["depth"] = DepthJson(depth);
    summary["depth"]["sample_ceiling"] = CoverageJson(ceiling.Summary());
  }
  AAVIO_RETURN_IF_ERROR(io::WriteTextFile((fs::path(options.out_dir) / "summary.json").string(),
                                          summary.dump(2) + "\n"));
  ctx.out << StrFormat(
      "mapped %.2f s of data in %.1f s (real-time factor %.2f): %lld cycles, %.0f "
      "map points on average\n",
      data_s, wall_s, wall_s > 0.0 ? data_s / wall_s : 0.0, static_cast<long long>(cycles),
      cycles > 0 ? static_cast<double>(map_points_sum) / cycles : 0.0);
  if (!gt_depth.empty()) ctx.out << DepthTable(depth) << SampleCeilingLine(ceiling.Summary());
  ctx.out << "wrote " << options.out_dir << "/{config.yaml,summary.json}\n";
  return Status::Ok();
}

}  // namespace

void RegisterRun(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand(
      "run",
      "Run the odometry on a sequence (or mapping only: --gt-poses, tracking only: --gt-map)");
  sub->add_option("sequence", options->sequence, "sequence.yaml, DSEC folder or bag")->required();
  sub->add_option("--out", options->out_dir, "Output folder")->required();
  sub->add_option("--calib", options->calibration, "Calibration, if the sequence names none");
  sub->add_flag("--gt-poses", options->gt_poses,
                "Mapping only, with the sequence's ground-truth poses instead of tracking");
  sub->add_flag("--esvo", options->esvo,
                "ESVO-like mode: newest-event selection of 10k points, static stereo only, no "
                "IMU prior");
  sub->add_flag("--real-time", options->real_time,
                "Maps reach tracking as soon as they are done and cycles are skipped while one "
                "runs (pipeline.real_time): for live input, not bit-reproducible");
  sub->add_flag("--gt-map", options->gt_map,
                "Tracking only, against maps built from the sequence's ground-truth depth");
  sub->add_option("--start", options->start_s, "Seconds to skip")->check(CLI::NonNegativeNumber);
  sub->add_option("--duration", options->duration_s, "Seconds to process (default: all)")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--quiet", options->quiet, "No progress output");
  AddConfigOptions(*sub, &options->config);
  sub->callback([&ctx, options] {
    ctx.action = [&ctx, options] {
      if (options->gt_poses && options->gt_map) {
        ctx.err << "aavio run: --gt-poses (mapping only) and --gt-map (tracking only) exclude "
                   "each other; give neither for the full odometry\n";
        return static_cast<int>(kExitUsage);
      }
      const Status status = Run(*options, ctx);
      if (status.ok()) return static_cast<int>(kExitOk);
      ctx.err << "aavio run: error: " << status.message() << "\n";
      return static_cast<int>(kExitError);
    };
  });
}

}  // namespace aavio::cli
