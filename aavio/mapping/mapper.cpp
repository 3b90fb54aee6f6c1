#include "aavio/mapping/mapper.hpp"

#include <chrono>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "aavio/common/format.hpp"
#include "aavio/mapping/depth_refinement.hpp"
#include "aavio/mapping/edge_snapping.hpp"
#include "aavio/mapping/out_of_view_check.hpp"
#include "aavio/mapping/sgm_bootstrap.hpp"
#include "aavio/mapping/static_stereo.hpp"
#include "aavio/mapping/temporal_stereo.hpp"

namespace aavio::mapping {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

cv::Mat ToFloat(const cv::Mat& image, bool smooth) {
  cv::Mat out;
  if (smooth) {
    cv::Mat blurred;
    cv::GaussianBlur(image, blurred, cv::Size(5, 5), 0.0, 0.0, cv::BORDER_REFLECT_101);
    blurred.convertTo(out, CV_32F);
  } else {
    image.convertTo(out, CV_32F);
  }
  return out;
}

// Samples used this cycle: at most max_points (evenly strided, order kept), away from the border
// (8 px top/left, 4 px bottom/right, in raw and rectified coordinates, as the reference).
std::vector<events::EdgeSample> UsableSamples(const events::Observation& obs, int width, int height,
                                              int max_points) {
  auto inside = [&](double x, double y) {
    return x >= 8 && y >= 8 && x < width - 4 && y < height - 4;
  };
  std::vector<events::EdgeSample> kept;
  for (const events::EdgeSample& s : obs.samples) {
    if (inside(s.x, s.y) && inside(s.u, s.v)) kept.push_back(s);
  }
  if (static_cast<int>(kept.size()) <= max_points) return kept;
  std::vector<events::EdgeSample> strided;
  strided.reserve(static_cast<std::size_t>(max_points));
  for (int i = 0; i < max_points; ++i)
    strided.push_back(kept[static_cast<std::size_t>(i) * kept.size() / max_points]);
  return strided;
}

}  // namespace

std::vector<events::EdgeSample> MappingSamples(const events::Observation& obs,
                                               const RectifiedStereo& stereo,
                                               const MappingConfig& config) {
  std::vector<events::EdgeSample> samples =
      UsableSamples(obs, stereo.width, stereo.height, config.max_points);
  if (config.snap_to_edge_px > 0.0) {
    SnapToNewestEdge(obs.negative_ts_left, obs.grad_u, obs.grad_v, config.snap_to_edge_px,
                     &samples);
  }
  return samples;
}

void MoveOntoNewestEdge(const std::vector<Eigen::Vector2f>& matched_at,
                        const std::vector<Eigen::Vector2f>& snapped,
                        std::vector<DepthPoint>* points) {
  std::size_t j = 0;
  for (DepthPoint& p : *points) {
    if (p.kind != StereoKind::kTemporal) continue;
    while (j < matched_at.size() && (matched_at[j].x() != p.u || matched_at[j].y() != p.v))
      ++j;
    if (j == matched_at.size()) return;
    p.u = snapped[j].x();
    p.v = snapped[j].y();
  }
}

Mapper::Mapper(const RectifiedStereo& stereo, const cv::Mat& valid_mask,
               const MappingConfig& config)
    : stereo_(stereo),
      valid_mask_(valid_mask),
      config_(config),
      fusion_(stereo, config.fusion,
              {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
               config.regularization.enabled}) {}

void Mapper::Reset() {
  fusion_.Clear();
  initialized_ = false;
  local_map_.reset();
}

void Mapper::Publish(const DepthMap& map, bool confirmed) {
  auto local = std::make_shared<LocalMap>();
  local->confirmed = confirmed;
  local->t_ns = map.t_ns();
  local->T_world_ref = map.T_world_frame();
  local->points = map.Points();
  local->points_world.reserve(local->points.size());
  for (const DepthPoint& p : local->points)
    local->points_world.push_back(map.T_world_frame() * p.Point(stereo_));
  local_map_ = std::move(local);
}

Status Mapper::Initialize(const PosedObservation& now, bool small_map_ok) {
  Expected<std::vector<DepthPoint>> points = Bootstrap(*now.obs);
  if (!points) return points.status();
  if (!small_map_ok && points->size() < static_cast<std::size_t>(config_.bootstrap.min_points)) {
    return FailedPrecondition(StrFormat(
        "the bootstrap found %zu points, fewer than mapping.bootstrap.min_points = %d: a smaller "
        "first map waits until the IMU shows the camera moving (a still camera's noise can give "
        "one)",
        points->size(), config_.bootstrap.min_points));
  }
  fusion_.Clear();
  DepthMap map(stereo_, now.T_world_obs, now.obs->t_ns);
  for (const DepthPoint& p : *points)
    map.InsertNaive(p);
  fusion_.Add(StereoKind::kStatic, {now.obs->t_ns, now.T_world_obs, std::move(*points)});
  Publish(map, /*confirmed=*/true);
  initialized_ = true;
  return Status::Ok();
}

Expected<std::vector<DepthPoint>> Mapper::Bootstrap(const events::Observation& obs) const {
  const BootstrapConfig& bootstrap = config_.bootstrap;
  if (bootstrap.method == BootstrapMethod::kBlockMatching) {
    const std::vector<events::EdgeSample> samples = MappingSamples(obs, stereo_, config_);
    std::vector<Eigen::Vector2f> positions;
    for (const events::EdgeSample& s : samples)
      positions.emplace_back(s.u, s.v);
    const bool smooth = config_.static_stereo.smooth_time_surface;
    const cv::Mat left = ToFloat(obs.ts_left, smooth), right = ToFloat(obs.ts_right, smooth);
    const std::vector<Match> matches =
        MatchStatic({left, right, valid_mask_}, positions, stereo_, config_.static_stereo,
                    config_.inv_depth_range());
    std::vector<DepthPoint> points =
        RefineDepths({left, right, nullptr, nullptr, {}}, matches, stereo_,
                     config_.depth_refinement, {}, config_.inv_depth_range());
    if (!bootstrap.Accepts(points.size(), samples.size()))
      return FailedPrecondition(bootstrap.Refusal("block-matching", points.size(), samples.size()));
    for (DepthPoint& p : points)
      p.age = kMinAge;  // survives the first cleanings, as SGM points
    return points;
  }
  std::vector<Eigen::Vector2f> positions;
  for (const events::EdgeSample& s : obs.samples)
    positions.emplace_back(s.u, s.v);
  return BootstrapWithSgm(obs.ts_left, obs.ts_right, positions, stereo_, bootstrap,
                          config_.depth_refinement.student_t_nu, config_.inv_depth_range());
}

Status Mapper::Update(const PosedObservation& now, const PosedObservation* partner,
                      MappingCycleReport* report, const PosedObservation* check) {
  const auto start = Clock::now();
  *report = MappingCycleReport{};
  const events::Observation& obs = *now.obs;
  std::vector<events::EdgeSample> samples =
      UsableSamples(obs, stereo_.width, stereo_.height, config_.max_points);
  // Temporal stereo compares AA maps, so it matches each sample where the AA map has it, before
  // the snap to the time surface's newest edge, and the point then moves onto the snapped
  // position (MoveOntoNewestEdge).
  const std::vector<events::EdgeSample> on_aa_map = samples;
  if (config_.snap_to_edge_px > 0.0)
    SnapToNewestEdge(obs.negative_ts_left, obs.grad_u, obs.grad_v, config_.snap_to_edge_px,
                     &samples);
  report->samples = static_cast<int>(samples.size());
  if (report->samples < kMinSamples) {
    report->total_ms = MsSince(start);
    return Status::Ok();  // too little to map this cycle; the old map stays published
  }

  // η split (docs/mapping.md): |g_u| / |g_v| < η → near-horizontal edge → temporal stereo.
  const bool temporal = config_.temporal_stereo.enabled;
  report->has_partner = partner != nullptr;
  std::vector<Eigen::Vector2f> static_group, temporal_group, temporal_snapped;
  std::vector<char> static_horizontal;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const events::EdgeSample& s = samples[i];
    const int u = static_cast<int>(std::lround(s.u)), v = static_cast<int>(std::lround(s.v));
    double gu = std::abs(obs.grad_u.at<float>(v, u)), gv = std::abs(obs.grad_v.at<float>(v, u));
    if (gu <= 0.01) gu = 0.1;
    if (gv <= 0.01) gv = 0.1;
    const bool horizontal = gu / gv < config_.eta;
    if (horizontal && temporal && partner != nullptr) {
      const events::EdgeSample& m = on_aa_map[i];
      temporal_group.emplace_back(m.u, m.v);
      temporal_snapped.emplace_back(s.u, s.v);
    }
    if (!horizontal || !temporal) {
      static_group.emplace_back(s.u, s.v);
      static_horizontal.push_back(horizontal ? 1 : 0);
    }
  }
  report->static_candidates = static_cast<int>(static_group.size());
  report->temporal_candidates = static_cast<int>(temporal_group.size());

  // Matching.
  auto t = Clock::now();
  const bool smooth = config_.static_stereo.smooth_time_surface;
  const cv::Mat left = ToFloat(obs.ts_left, smooth), right = ToFloat(obs.ts_right, smooth);
  std::vector<Match> matches = MatchStatic({left, right, valid_mask_}, static_group, stereo_,
                                           config_.static_stereo, config_.inv_depth_range());
  // Remember which static matches sit on near-horizontal edges (for the evaluation split).
  {
    std::size_t k = 0;
    for (std::size_t i = 0; i < static_group.size() && k < matches.size(); ++i) {
      if (static_group[i].x() == matches[k].u && static_group[i].y() == matches[k].v) {
        matches[k++].near_horizontal = static_horizontal[i] != 0;
      }
    }
  }
  if (config_.static_stereo.out_of_view_radius_px > 0 && local_map_) {
    DropOutOfViewMatches(*local_map_, now.T_world_obs, stereo_, kPatchWidth / 2,
                         config_.static_stereo.out_of_view_radius_px, &matches);
  }
  report->static_matches = static_cast<int>(matches.size());
  cv::Mat aa_now, aa_past;
  geometry::RigidTransform T_past_now;
  if (!temporal_group.empty()) {
    const bool smooth_aa = config_.temporal_stereo.smooth_aa;
    aa_now = ToFloat(obs.aa_map, smooth_aa);
    aa_past = ToFloat(partner->obs->aa_map, smooth_aa);
    T_past_now = partner->T_world_obs.Inverse() * now.T_world_obs;
    TemporalStereoInput input{aa_now, aa_past, T_past_now};
    cv::Mat aa_check;
    geometry::RigidTransform T_check_now;
    if (check != nullptr) {
      aa_check = ToFloat(check->obs->aa_map, smooth_aa);
      T_check_now = check->T_world_obs.Inverse() * now.T_world_obs;
      input.aa_check = &aa_check;
      input.T_check_now = &T_check_now;
    }
    const std::vector<Match> temporal_matches = MatchTemporal(
        input, temporal_group, stereo_, config_.temporal_stereo,
        config_.static_stereo.zncc_threshold, config_.inv_depth_range(), &report->temporal);
    report->temporal_matches = static_cast<int>(temporal_matches.size());
    matches.insert(matches.end(), temporal_matches.begin(), temporal_matches.end());
  }
  report->matching_ms = MsSince(t);

  // Refinement and culling.
  t = Clock::now();
  const RefinementInput refine{left, right, aa_now.empty() ? nullptr : &aa_now,
                               aa_past.empty() ? nullptr : &aa_past, T_past_now};
  std::vector<DepthPoint> refined = RefineDepths(
      refine, matches, stereo_, config_.depth_refinement,
      {config_.temporal_stereo.max_inv_depth_stddev, config_.temporal_stereo.residual_threshold},
      config_.inv_depth_range());
  MoveOntoNewestEdge(temporal_group, temporal_snapped, &refined);
  report->refinement_ms = MsSince(t);

  // Fusion: one batch per kind, then a new map at the current pose.
  t = Clock::now();
  DepthBatch static_batch{obs.t_ns, now.T_world_obs, {}},
      temporal_batch{obs.t_ns, now.T_world_obs, {}};
  for (const DepthPoint& p : refined)
    (p.kind == StereoKind::kStatic ? static_batch : temporal_batch).points.push_back(p);
  report->static_points = static_cast<int>(static_batch.points.size());
  report->temporal_points = static_cast<int>(temporal_batch.points.size());
  fusion_.Add(StereoKind::kStatic, std::move(static_batch));
  if (!temporal_batch.points.empty()) fusion_.Add(StereoKind::kTemporal, std::move(temporal_batch));
  const DepthMap map = fusion_.Fuse(now.T_world_obs, obs.t_ns);
  report->map_points = static_cast<int>(map.size());
  report->fused_cycles = static_cast<int>(fusion_.static_batches());
  // Depth outputs take cleaned maps only; tracking gets what the reference codes publish, or
  // every map with publish_while_filling.
  if (fusion_.ready_to_publish() || config_.fusion.publish_while_filling) {
    Publish(map, /*confirmed=*/fusion_.full());
    report->published = true;
  }
  report->fusion_ms = MsSince(t);
  report->total_ms = MsSince(start);
  return Status::Ok();
}

}  // namespace aavio::mapping
