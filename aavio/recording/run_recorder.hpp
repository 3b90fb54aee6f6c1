#pragma once
/// What a run leaves in its output folder, whichever way it is driven (docs/cli.md): the CLI's
/// `aavio run` in each of its modes, and any front end that feeds the odometry live. Fed with the
/// odometry's ticks (or, when mapping runs on ground-truth poses, with its mapping cycles), it
/// keeps the trajectory, the per-stage timings and the status counts; writes timings.csv as it
/// goes, every confirmed local map into the global cloud and five a second into `depth/`; scores
/// depth against the sequence's ground truth as the maps are made (no file is read back); and at
/// Finish writes stamped_traj_estimate.txt, map.ply, config.yaml and summary.json. The trajectory
/// and the cloud are on disk as they grow (as .part files), and 16 MB are held back from the start
/// (io::DiskReserve), so that a run stopped by a full disk still finishes with valid outputs.

#include <array>
#include <chrono>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aavio/eval/sample_ceiling.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/imu/gravity_direction.hpp"
#include "aavio/io/output_folder.hpp"
#include "aavio/io/trajectory_writing.hpp"
#include "aavio/pipeline/mapping_front_end.hpp"
#include "aavio/pipeline/odometry.hpp"
#include "aavio/pipeline/stage_timings.hpp"
#include "aavio/recording/depth_scorer.hpp"
#include "aavio/recording/event_gaps.hpp"
#include "aavio/recording/map_outputs.hpp"
#include "aavio/recording/mapping_counts.hpp"
#include "aavio/recording/run_evaluation.hpp"
#include "aavio/recording/run_files.hpp"
#include "aavio/recording/tick_counts.hpp"
#include "aavio/recording/timings_csv.hpp"

namespace aavio::recording {

struct RunRecorderOptions {
  std::string out_dir;
  /// A folder holding an earlier run is refused unless this is set; then that run's files are
  /// removed first (io::PrepareOutputFolder).
  bool overwrite = false;
  std::string mode = "full";  ///< summary.json "mode"
  std::string sequence;       ///< summary.json "sequence": what `aavio eval --run` reopens
  std::string calibration;    ///< summary.json "calibration": the one the run used
  std::string config_yaml;    ///< the effective configuration, written as config.yaml
  std::string version;        ///< summary.json "version": the program's, with its git revision
  TimeNs begin_ns = 0;        ///< the data time the run starts at
  /// Also write the trajectory in this format (io::TrajectoryFileName), at `poses_at`
  /// (interpolated, geometry::SampleAt) when that is not empty, else at every pose. kTum with
  /// no stamps writes nothing more (stamped_traj_estimate.txt is TUM).
  io::TrajectoryFormat format = io::TrajectoryFormat::kTum;
  std::vector<TimeNs> poses_at;
  /// The world of the poses the recorder is given, and of the files it writes (summary.json
  /// `world.frame`).
  enum class World {
    kFirstCamera,  ///< the odometry's: its first camera's frame
    kGroundTruth,  ///< the modes on ground truth: the ground truth's
    /// The first camera's, written turned z-up along the gravity the run measured (motion.gravity
    /// q_up_world) — if it measured one, else left as it is (`world.frame` says which).
    kGravity,
  };
  World world = World::kFirstCamera;
};

/// A finished run's figures (summary.json holds the same).
struct RunRecord {
  nlohmann::json summary;
  double data_s = 0.0, wall_s = 0.0;
  /// CPU time of every thread of the process from Open to Finish [s]; summary.json "cpu_s" and
  /// "cpu_s_per_data_s" leave the scoring out, as "real_time_factor" does.
  double cpu_s = 0.0;
  std::optional<TrajectoryEvaluation> accuracy;
  /// Why there is no accuracy although the sequence has a ground truth (summary.json
  /// "accuracy_error"): e.g. fewer than 10 poses to score.
  Status accuracy_error = Status::Ok();
  std::optional<eval::DepthErrorSummary> depth;
  std::optional<eval::DepthErrorSummary> sample_ceiling;  ///< runs on ground-truth poses
  /// The calibration's error against the sequence's true one (RunGroundTruth).
  std::optional<geometry::CalibrationDifference> calibration_error;
  double fb = 0.0;  ///< the calibration's focal length × baseline [px·m]
};

class RunRecorder {
 public:
  /// Creates `options.out_dir`, removing the files an earlier run wrote there.
  static Expected<std::unique_ptr<RunRecorder>> Open(RunRecorderOptions options,
                                                     const geometry::StereoRig& rig,
                                                     const pipeline::OdometryConfig& config);

  /// Scores the run against this ground truth: the trajectory at Finish, and the depth maps as
  /// they come if it has depth. Call before the first tick.
  Status SetGroundTruth(const RunGroundTruth& truth, std::vector<geometry::StampedPose> gt_poses);

  /// A packet of events read, and the time reading it took.
  void AddPacket(std::size_t events, double reading_ms);
  /// IMU samples read: with the rig's IMU extrinsic, the run's gravity direction (summary.json
  /// "gravity", imu::GravityDirectionEstimator).
  void AddImu(const std::vector<imu::ImuSample>& samples) {
    for (const imu::ImuSample& s : samples)
      gravity_.Add(s);
  }
  /// The time of a stage the ticks do not report (e.g. "event_insertion").
  void AddStage(const std::string& stage, double ms, double items = 0.0) {
    timings_.Add(stage, ms, items);
  }
  /// A tick of pipeline::Odometry (full odometry, or tracking alone).
  Status AddTick(const pipeline::OdometryTick& tick);
  /// A tick of pipeline::MappingFrontEnd (mapping on ground-truth poses), and its cycles: every
  /// confirmed map is scored with its points as they are (the world is the ground truth's), with
  /// what its edge samples would cover at their true depth beside it.
  void AddMappingTick(TimeNs t_ns, const events::RepresentationTimings& timings);
  Status AddMappingCycle(const pipeline::MappingCycle& cycle);

  /// Writes everything. `end_ns`: the data time processed up to; `extra` is merged into
  /// summary.json. Writes every file it can even after a failure (a full disk: the space held
  /// back is released first), lists the failures in summary.json "incomplete_outputs" and then
  /// returns the first.
  Expected<RunRecord> Finish(bool interrupted, TimeNs end_ns,
                             const nlohmann::json& extra = nlohmann::json::object());

  const std::vector<geometry::StampedPose>& trajectory() const { return trajectory_; }
  /// Ticks per tracking status so far ("ok", "lost", "no_map").
  const std::map<std::string, int>& status_counts() const { return counts_.status_counts(); }
  /// Ticks were run and none had a map (TickCounts::NeverMapped): why, else "".
  std::string NeverMappedReason() const;
  const std::string& out_dir() const { return options_.out_dir; }

 private:
  RunRecorder(RunRecorderOptions options, const geometry::StereoRig& rig,
              const pipeline::OdometryConfig& config, MapOutputs maps, io::DiskReserve reserve);
  void AddRepresentation(TimeNs t_ns, const events::RepresentationTimings& t);
  void AddCycleReport(const mapping::MappingCycleReport& r);
  /// A confirmed map: into map.ply and depth/ (what went to depth/ scored there in the
  /// odometry's modes), drawn over the time surface of `observation` (may be null).
  Status AddConfirmedMap(const mapping::LocalMap& map, const events::Observation* observation,
                         bool score_written);
  /// A mapping cycle on ground-truth poses against the nearest ground-truth frame: the map's
  /// depth, and what its samples could cover at best.
  Status ScoreCycleOnGroundTruth(const pipeline::MappingCycle& cycle, bool confirmed);
  /// stamped_traj_estimate.txt from its part file, or from memory if a write to that failed.
  /// `rewrite`: the trajectory was turned since it was streamed; written again whole.
  Status CloseTrajectory(bool rewrite);
  /// Closes every file (the trajectory and map.ply turned z-up with World::kGravity and a
  /// measured gravity: `R_out_first`); failures into `failures`. Returns summary.json "motion".
  nlohmann::json CloseFiles(std::optional<Eigen::Matrix3d>* R_out_first,
                            std::vector<Status>* failures);
  /// The ground truth's scores of the run.
  void Score(RunRecord* record) const;
  /// summary.json's figures (in record->summary).
  void Summarize(bool interrupted, TimeNs end_ns, nlohmann::json motion,
                 const std::optional<Eigen::Matrix3d>& R_out_first, RunRecord* record);

  RunRecorderOptions options_;
  pipeline::OdometryConfig config_;
  mapping::RectifiedStereo stereo_;
  std::optional<geometry::RigidTransform> T_imu_cam_;  // the rig's IMU ← rectified left camera
  imu::GravityDirectionEstimator gravity_;
  std::chrono::steady_clock::time_point wall_start_;
  double cpu_start_s_ = 0.0;  ///< the process's CPU time at Open [s]
  // What it writes as the run goes.
  MapOutputs maps_;
  TimingsCsv csv_;
  std::ofstream trajectory_file_;  ///< the poses (stamped_traj_estimate.txt.part)
  std::optional<io::DiskReserve> reserve_;
  // What it scores against.
  std::optional<RunGroundTruth> truth_;
  std::vector<geometry::StampedPose> gt_poses_;
  std::optional<DepthScorer> scorer_;
  std::optional<eval::SampleCeiling> ceiling_;
  int mapping_cycles_on_ground_truth_ = 0;  ///< AddMappingCycle's
  double evaluation_ms_ = 0.0;              ///< scoring depth: not part of the real-time factor
  // What it counts.
  std::vector<geometry::StampedPose> trajectory_;
  TickCounts counts_;
  pipeline::StageTimings timings_;
  MappingCounts mapping_counts_;
  EventGaps event_gaps_;
  std::int64_t events_ = 0, ticks_ = 0;
  nlohmann::json over_time_ = nlohmann::json::array();  ///< [data s, resident MB, wall s]
};

}  // namespace aavio::recording
