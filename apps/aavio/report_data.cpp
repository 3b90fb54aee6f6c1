#include "report_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "aavio/common/format.hpp"
#include "aavio/geometry/velocity.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/run_evaluation.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Plots need no more than this many samples of a curve (keeps the data of long runs small).
constexpr std::size_t kMaxCurveSamples = 5000;
constexpr std::size_t kMaxDepthPoints = 200000;

// At most `n` evenly spaced indices of [0, size).
std::vector<std::size_t> ThinIndices(std::size_t size, std::size_t n) {
  std::vector<std::size_t> out;
  const std::size_t count = std::min(size, n);
  for (std::size_t i = 0; i < count; ++i)
    out.push_back(size <= n ? i : i * size / n);
  return out;
}

template <typename T>
std::vector<T> Thin(const std::vector<T>& v, std::size_t n) {
  std::vector<T> out;
  for (const std::size_t i : ThinIndices(v.size(), n))
    out.push_back(v[i]);
  return out;
}

json Vec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

json QuaternionXyzw(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return {q.x(), q.y(), q.z(), q.w()};
}

// The velocity of `velocities` (sorted, one per pose) nearest `t_ns`, if valid.
const geometry::StampedVelocity* Nearest(const std::vector<geometry::StampedVelocity>& velocities,
                                         TimeNs t_ns) {
  if (velocities.empty()) return nullptr;
  auto it =
      std::lower_bound(velocities.begin(), velocities.end(), t_ns,
                       [](const geometry::StampedVelocity& v, TimeNs t) { return v.t_ns < t; });
  if (it == velocities.end() ||
      (it != velocities.begin() && t_ns - (it - 1)->t_ns < it->t_ns - t_ns))
    --it;
  if (it == velocities.end() || !it->valid) return nullptr;
  return &*it;
}

// The trajectory against the ground truth: aligned positions and orientations, the error of each
// pose, the velocities of both (body frame), thinned for the plots.
Expected<json> TrajectoryData(const std::string& estimate_path,
                              const std::vector<geometry::StampedPose>& gt) {
  Expected<std::vector<geometry::StampedPose>> est = io::ReadTumTrajectory(estimate_path);
  if (!est) return est.status();
  Expected<recording::TrajectoryEvaluation> e = recording::EvaluateTrajectories(*est, gt, {});
  if (!e) return e.status().WithContext(estimate_path);
  json ev = recording::TrajectoryEvaluationJson(*e);
  const eval::Similarity& S = e->absolute.alignment;
  ev["alignment_R"] = {Vec(S.R.row(0)), Vec(S.R.row(1)), Vec(S.R.row(2))};
  const std::vector<geometry::StampedVelocity> v_est =
      geometry::EstimateVelocities(*est, geometry::kDefaultVelocityHalfWindowNs);
  const std::vector<geometry::StampedVelocity> v_gt =
      geometry::EstimateVelocities(gt, geometry::kDefaultVelocityHalfWindowNs);
  const std::vector<double> distance = eval::DistanceFromStart(e->pairs);
  json t = json::array(), p_gt = json::array(), p_est = json::array(), q_gt = json::array(),
       q_est = json::array(), ate = json::array(), dist = json::array(), vel_gt = json::array(),
       vel_est = json::array();
  const TimeNs t0 = e->pairs.front().t_ns;
  for (const std::size_t i : ThinIndices(e->pairs.size(), kMaxCurveSamples)) {
    const eval::PosePair& p = e->pairs[i];
    t.push_back(NsToSeconds(p.t_ns - t0));
    p_gt.push_back(Vec(p.T_world_gt.t));
    p_est.push_back(Vec(S.Apply(p.T_world_est.t)));
    q_gt.push_back(QuaternionXyzw(p.T_world_gt.R));
    q_est.push_back(QuaternionXyzw(S.R * p.T_world_est.R));
    ate.push_back(e->absolute.ate_per_pair_m[i]);
    dist.push_back(distance[i]);
    const geometry::StampedVelocity* a = Nearest(v_est, p.t_ns);
    const geometry::StampedVelocity* b = Nearest(v_gt, p.t_ns);
    vel_est.push_back(a ? Vec(a->v_body_mps) : json(nullptr));
    vel_gt.push_back(b ? Vec(b->v_body_mps) : json(nullptr));
  }
  ev["t_s"] = t;
  ev["positions_gt"] = p_gt;
  ev["positions_est_aligned"] = p_est;
  ev["q_gt_xyzw"] = q_gt;
  ev["q_est_aligned_xyzw"] = q_est;
  ev["ate_m"] = ate;
  ev["distance_m"] = dist;
  ev["v_gt_body_mps"] = vel_gt;
  ev["v_est_body_mps"] = vel_est;
  ev["relative"] = json::array();
  for (const eval::SubTrajectoryErrors& s : e->relative.per_length) {
    ev["relative"].push_back({{"length_m", s.length_m},
                              {"trans_pct", Thin(s.trans_pct, 2000)},
                              {"rot_deg_per_m", Thin(s.rot_deg_per_m, 2000)}});
  }
  return ev;
}

Status WriteFloatImage(const fs::path& path, const cv::Mat& image) {
  std::ofstream out(path, std::ios::binary);
  for (int y = 0; y < image.rows; ++y) {
    const float* row = image.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      const float z = row[x] > 0.0f ? row[x] : std::numeric_limits<float>::quiet_NaN();
      out.write(reinterpret_cast<const char*>(&z), sizeof z);
    }
  }
  if (!out) return IoError(path.string() + ": write failed (disk full?)");
  return Status::Ok();
}

// Depth errors point by point (true depth, estimate, kind), and kReportDepthFrames maps spread
// over the run beside the ground truth's frame and where their points fell in it.
Expected<json> DepthData(const fs::path& run_depth_dir, const recording::RunGroundTruth& truth,
                         const std::vector<geometry::StampedPose>& gt, const fs::path& data_dir,
                         const std::string& prefix) {
  std::vector<io::GtDepthEntry> scored;
  Expected<eval::DepthErrorAccumulator> depth =
      recording::EvaluateRunDepth(run_depth_dir.string(), truth, gt, &scored);
  if (!depth) return depth.status();
  const std::vector<eval::ScoredDepthPoint>& points = depth->points();
  json out;
  out["summary"] = recording::DepthJson(depth->Summary());
  json z_gt = json::array(), z_est = json::array(), kind = json::array();
  for (const std::size_t i : ThinIndices(points.size(), kMaxDepthPoints)) {
    z_gt.push_back(points[i].z_gt_m);
    z_est.push_back(points[i].z_est_m);
    kind.push_back(points[i].kind);
  }
  out["points"] = {{"z_gt_m", z_gt}, {"z_est_m", z_est}, {"kind", kind}};
  Expected<std::vector<io::GtDepthEntry>> gt_frames = io::ReadGtDepthIndex(truth.depth_dir);
  if (!gt_frames) return gt_frames.status();
  out["frames"] = json::array();
  if (scored.empty() || gt_frames->empty()) return out;
  const int shown = std::min<int>(kReportDepthFrames, static_cast<int>(scored.size()));
  for (int k = 0; k < shown; ++k) {
    // Spread evenly: the middle of each of `shown` equal stretches of the run (the first map,
    // still thin, is not one of them).
    const std::size_t f =
        shown == 1 ? 0 : static_cast<std::size_t>((k + 0.5) * scored.size() / shown);
    const io::GtDepthEntry& entry = scored[f];
    Expected<io::GtDepthFrame> estimate =
        io::LoadGtDepthFrame(run_depth_dir.string(), entry, truth.fb, truth.disparity_offset);
    if (!estimate) return estimate.status();
    const auto nearest =
        std::min_element(gt_frames->begin(), gt_frames->end(),
                         [&](const io::GtDepthEntry& a, const io::GtDepthEntry& b) {
                           return std::llabs(a.t_ns - entry.t_ns) < std::llabs(b.t_ns - entry.t_ns);
                         });
    Expected<io::GtDepthFrame> truth_frame =
        io::LoadGtDepthFrame(truth.depth_dir, *nearest, truth.fb, truth.disparity_offset);
    if (!truth_frame) return truth_frame.status();
    const std::string est_name = StrFormat("%s_depth_%d.f32", prefix.c_str(), k);
    const std::string gt_name = StrFormat("%s_truth_%d.f32", prefix.c_str(), k);
    AAVIO_RETURN_IF_ERROR(WriteFloatImage(data_dir / est_name, estimate->depth_m));
    AAVIO_RETURN_IF_ERROR(WriteFloatImage(data_dir / gt_name, truth_frame->depth_m));
    json u = json::array(), v = json::array(), error = json::array();
    for (const eval::ScoredDepthPoint& p : points) {
      if (p.frame != f) continue;
      u.push_back(p.u);
      v.push_back(p.v);
      error.push_back(p.z_est_m - p.z_gt_m);
    }
    out["frames"].push_back({{"t_ns", entry.t_ns},
                             {"truth_t_ns", nearest->t_ns},
                             {"width", estimate->depth_m.cols},
                             {"height", estimate->depth_m.rows},
                             {"estimate", est_name},
                             {"truth", gt_name},
                             {"u", u},
                             {"v", v},
                             {"error_m", error}});
  }
  return out;
}

// config.yaml as key → value (what the report compares between runs); empty if there is none.
json ConfigOf(const fs::path& dir) {
  json config = json::object();
  const fs::path path = dir / recording::run_files::kConfig;
  if (!fs::exists(path)) return config;
  Expected<std::vector<ConfigEntry>> entries = io::ReadConfigYaml(path.string());
  if (!entries) return config;
  for (const ConfigEntry& e : *entries) {
    if (!e.value.is_list) {
      config[e.key] = e.value.scalar;
      continue;
    }
    std::string list;
    for (const std::string& item : e.value.list)
      list += (list.empty() ? "" : ", ") + item;
    config[e.key] = "[" + list + "]";
  }
  return config;
}

}  // namespace

Expected<json> GatherReportRun(const ReportRun& run, const fs::path& data_dir,
                               const std::string& prefix, Context& ctx) {
  Expected<RunInputs> inputs = ReadRunInputs(run.dir, "", run.calibration);
  if (!inputs) return inputs.status();
  json out;
  out["summary"] = inputs->summary;
  out["name"] = run.name;
  out["dir"] = fs::absolute(run.dir).string();
  out["config"] = ConfigOf(run.dir);
  Expected<recording::RunGroundTruth> truth = LoadRunGroundTruth(*inputs);
  if (!truth) {
    ctx.err << "aavio report: " << run.dir << ": no ground truth to evaluate against ("
            << truth.status().message() << "); the run's own figures only\n";
    return out;
  }
  Expected<std::vector<geometry::StampedPose>> gt = truth->ReadPoses();
  if (!gt) return gt.status();
  // A run on ground-truth poses has depth maps but no trajectory of its own.
  const fs::path estimate_path = fs::path(run.dir) / recording::run_files::kTrajectory;
  if (fs::exists(estimate_path)) {
    Expected<json> ev = TrajectoryData(estimate_path.string(), *gt);
    if (!ev) return ev.status();
    out["evaluation"] = *ev;
  }
  const fs::path depth_dir = fs::path(run.dir) / recording::run_files::kDepthDir;
  if (!truth->depth_dir.empty() && fs::exists(depth_dir / "timestamps.txt")) {
    Expected<json> depth = DepthData(depth_dir, *truth, *gt, data_dir, prefix);
    if (!depth) return depth.status();
    out["depth"] = *depth;
  }
  return out;
}

}  // namespace aavio::cli
