#include "aavio/mapping/mapper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "aavio/common/format.hpp"
#include "aavio/mapping/depth_refinement.hpp"
#include "aavio/mapping/disparity_prediction.hpp"
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

// Whether the edge at a rectified position runs near-horizontally by the η rule (docs/mapping.md):
// |g_u| / |g_v| < η, an edge along which static stereo finds no disparity.
bool NearHorizontal(const events::Observation& obs, float su, float sv, double eta) {
  const int u = std::clamp(static_cast<int>(std::lround(su)), 0, obs.grad_u.cols - 1),
            v = std::clamp(static_cast<int>(std::lround(sv)), 0, obs.grad_u.rows - 1);
  double gu = std::abs(obs.grad_u.at<float>(v, u)), gv = std::abs(obs.grad_v.at<float>(v, u));
  if (gu <= 0.01) gu = 0.1;
  if (gv <= 0.01) gv = 0.1;
  return gu / gv < eta;
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
  const bool block_matching = bootstrap.method == BootstrapMethod::kBlockMatching;
  std::vector<Eigen::Vector2f> positions;
  if (block_matching) {
    for (const events::EdgeSample& s : MappingSamples(obs, stereo_, config_))
      positions.emplace_back(s.u, s.v);
  } else {
    for (const events::EdgeSample& s : obs.samples)
      positions.emplace_back(s.u, s.v);
  }
  Expected<std::vector<DepthPoint>> points =
      block_matching
          ? BlockMatchingBootstrap(obs, positions)
          : BootstrapWithSgm(obs.ts_left, obs.ts_right, positions, stereo_,
                             config_.depth_refinement.student_t_nu, config_.inv_depth_range());
  if (!points) return points.status();
  // What the scene offers: the samples static stereo can match, not those along near-horizontal
  // edges (a drone's climb past a wall's courses of bricks gives few others).
  const std::size_t matchable = static_cast<std::size_t>(std::count_if(
      positions.begin(), positions.end(),
      [&](const Eigen::Vector2f& x) { return !NearHorizontal(obs, x.x(), x.y(), config_.eta); }));
  if (!bootstrap.Accepts(points->size(), matchable)) {
    return FailedPrecondition(bootstrap.Refusal(block_matching ? "block-matching" : "SGM",
                                                points->size(), matchable, positions.size()));
  }
  return points;
}

std::vector<DepthPoint> Mapper::BlockMatchingBootstrap(
    const events::Observation& obs, const std::vector<Eigen::Vector2f>& positions) const {
  const bool smooth = config_.static_stereo.smooth_time_surface;
  const cv::Mat left = ToFloat(obs.ts_left, smooth), right = ToFloat(obs.ts_right, smooth);
  const std::vector<Match> matches = MatchStatic({left, right, valid_mask_}, positions, stereo_,
                                                 config_.static_stereo, config_.inv_depth_range());
  std::vector<DepthPoint> points =
      RefineDepths({left, right, nullptr, nullptr, {}}, matches, stereo_, config_.depth_refinement,
                   {}, config_.inv_depth_range());
  for (DepthPoint& p : points)
    p.age = kMinAge;  // survives the first cleanings, as SGM points
  return points;
}

namespace {

// A cycle's samples split by the η rule (docs/mapping.md): |g_u| / |g_v| < η is a near-horizontal
// edge, matched by temporal stereo when it is on and there is a partner — at the sample's AA-map
// position (`on_aa_map`), moved afterwards onto its snapped one — and skipped without a partner;
// the others go to static stereo.
struct SampleGroups {
  std::vector<Eigen::Vector2f> static_group, temporal_group, temporal_snapped;
  std::vector<char> static_horizontal;  // per static sample: on a near-horizontal edge
};

SampleGroups SplitByEta(const events::Observation& obs,
                        const std::vector<events::EdgeSample>& samples,
                        const std::vector<events::EdgeSample>& on_aa_map, double eta, bool temporal,
                        bool has_partner) {
  SampleGroups g;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const events::EdgeSample& s = samples[i];
    const bool horizontal = NearHorizontal(obs, s.u, s.v, eta);
    if (horizontal && temporal && has_partner) {
      const events::EdgeSample& m = on_aa_map[i];
      g.temporal_group.emplace_back(m.u, m.v);
      g.temporal_snapped.emplace_back(s.u, s.v);
    }
    if (!horizontal || !temporal) {
      g.static_group.emplace_back(s.u, s.v);
      g.static_horizontal.push_back(horizontal ? 1 : 0);
    }
  }
  return g;
}

// Marks the static matches that sit on near-horizontal edges (for the evaluation split).
void MarkNearHorizontal(const SampleGroups& g, std::vector<Match>* matches) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < g.static_group.size() && k < matches->size(); ++i) {
    if (g.static_group[i].x() == (*matches)[k].u && g.static_group[i].y() == (*matches)[k].v)
      (*matches)[k++].near_horizontal = g.static_horizontal[i] != 0;
  }
}

// The AA maps temporal stereo matched on, for refinement.
struct TemporalViews {
  cv::Mat aa_now, aa_past;
  geometry::RigidTransform T_past_now;
};

// Temporal stereo on `group`: now's AA map against the partner's (and the check partner's).
std::vector<Match> MatchTemporalGroup(const PosedObservation& now, const PosedObservation& partner,
                                      const PosedObservation* check,
                                      const std::vector<Eigen::Vector2f>& group,
                                      const RectifiedStereo& stereo, const MappingConfig& config,
                                      const DisparityPrediction* prediction, TemporalViews* views,
                                      TemporalMatchStats* stats) {
  const bool smooth_aa = config.temporal_stereo.smooth_aa;
  views->aa_now = ToFloat(now.obs->aa_map, smooth_aa);
  views->aa_past = ToFloat(partner.obs->aa_map, smooth_aa);
  views->T_past_now = partner.T_world_obs.Inverse() * now.T_world_obs;
  TemporalStereoInput input{views->aa_now, views->aa_past, views->T_past_now};
  cv::Mat aa_check;
  geometry::RigidTransform T_check_now;
  if (check != nullptr) {
    aa_check = ToFloat(check->obs->aa_map, smooth_aa);
    T_check_now = check->T_world_obs.Inverse() * now.T_world_obs;
    input.aa_check = &aa_check;
    input.T_check_now = &T_check_now;
  }
  return MatchTemporal(input, group, stereo, config.temporal_stereo,
                       config.static_stereo.zncc_threshold, config.inv_depth_range(), stats,
                       prediction);
}

}  // namespace

Status Mapper::Update(const PosedObservation& now, const PosedObservation* partner,
                      MappingCycleReport* report, const PosedObservation* check) {
  const auto start = Clock::now();
  *report = MappingCycleReport{};
  const events::Observation& obs = *now.obs;
  std::vector<events::EdgeSample> samples =
      UsableSamples(obs, stereo_.width, stereo_.height, config_.max_points);
  // Temporal stereo compares AA maps, so it matches each sample where the AA map has it, before
  // the snap to the time surface's newest edge (MoveOntoNewestEdge moves it afterwards).
  const std::vector<events::EdgeSample> on_aa_map = samples;
  if (config_.snap_to_edge_px > 0.0)
    SnapToNewestEdge(obs.negative_ts_left, obs.grad_u, obs.grad_v, config_.snap_to_edge_px,
                     &samples);
  report->samples = static_cast<int>(samples.size());
  if (report->samples < kMinSamples) {
    report->total_ms = MsSince(start);
    return Status::Ok();  // too little to map this cycle; the old map stays published
  }
  report->has_partner = partner != nullptr;
  const SampleGroups groups = SplitByEta(obs, samples, on_aa_map, config_.eta,
                                         config_.temporal_stereo.enabled, partner != nullptr);
  report->static_candidates = static_cast<int>(groups.static_group.size());
  report->temporal_candidates = static_cast<int>(groups.temporal_group.size());

  // Matching.
  auto t = Clock::now();
  const bool smooth = config_.static_stereo.smooth_time_surface;
  const cv::Mat left = ToFloat(obs.ts_left, smooth), right = ToFloat(obs.ts_right, smooth);
  std::optional<DisparityPrediction> prediction;
  if (config_.predicted_search && local_map_)
    prediction.emplace(*local_map_, now.T_world_obs, stereo_);
  std::vector<Match> matches =
      MatchStatic({left, right, valid_mask_}, groups.static_group, stereo_, config_.static_stereo,
                  config_.inv_depth_range(), prediction ? &*prediction : nullptr);
  MarkNearHorizontal(groups, &matches);
  if (config_.static_stereo.out_of_view_radius_px > 0 && local_map_) {
    DropOutOfViewMatches(*local_map_, now.T_world_obs, stereo_, kPatchWidth / 2,
                         config_.static_stereo.out_of_view_radius_px, &matches);
  }
  report->static_matches = static_cast<int>(matches.size());
  TemporalViews views;
  if (!groups.temporal_group.empty()) {
    const std::vector<Match> temporal_matches =
        MatchTemporalGroup(now, *partner, check, groups.temporal_group, stereo_, config_,
                           prediction ? &*prediction : nullptr, &views, &report->temporal);
    report->temporal_matches = static_cast<int>(temporal_matches.size());
    matches.insert(matches.end(), temporal_matches.begin(), temporal_matches.end());
  }
  report->matching_ms = MsSince(t);

  // Refinement and culling.
  t = Clock::now();
  const RefinementInput refine{left, right, views.aa_now.empty() ? nullptr : &views.aa_now,
                               views.aa_past.empty() ? nullptr : &views.aa_past, views.T_past_now};
  std::vector<DepthPoint> refined = RefineDepths(
      refine, matches, stereo_, config_.depth_refinement,
      {config_.temporal_stereo.max_inv_depth_stddev, config_.temporal_stereo.residual_threshold},
      config_.inv_depth_range());
  MoveOntoNewestEdge(groups.temporal_group, groups.temporal_snapped, &refined);
  report->refinement_ms = MsSince(t);

  FuseCycle(now, refined, report);
  report->total_ms = MsSince(start);
  return Status::Ok();
}

void Mapper::FuseCycle(const PosedObservation& now, const std::vector<DepthPoint>& refined,
                       MappingCycleReport* report) {
  // One batch per kind, then a new map at the current pose.
  const auto t = Clock::now();
  const TimeNs t_ns = now.obs->t_ns;
  DepthBatch static_batch{t_ns, now.T_world_obs, {}}, temporal_batch{t_ns, now.T_world_obs, {}};
  for (const DepthPoint& p : refined)
    (p.kind == StereoKind::kStatic ? static_batch : temporal_batch).points.push_back(p);
  report->static_points = static_cast<int>(static_batch.points.size());
  report->temporal_points = static_cast<int>(temporal_batch.points.size());
  fusion_.Add(StereoKind::kStatic, std::move(static_batch));
  if (!temporal_batch.points.empty()) fusion_.Add(StereoKind::kTemporal, std::move(temporal_batch));
  const DepthMap map = fusion_.Fuse(now.T_world_obs, t_ns);
  report->map_points = static_cast<int>(map.size());
  report->fused_cycles = static_cast<int>(fusion_.static_batches());
  // Depth outputs take cleaned maps only; tracking gets what the reference codes publish, or
  // every map with publish_while_filling.
  if (fusion_.ready_to_publish() || config_.fusion.publish_while_filling) {
    Publish(map, /*confirmed=*/fusion_.full());
    report->published = true;
  }
  report->fusion_ms = MsSince(t);
}

}  // namespace aavio::mapping
