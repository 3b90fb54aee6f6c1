#pragma once
/// One mapping cycle (docs/mapping.md): the current observation's edge samples are split by the
/// gradient ratio η into a static group (left/right TS matching) and a near-horizontal temporal
/// group (AA now vs AA of a partner observation), refined, pushed as batches into the fusion
/// FIFO, and fused into a new map at the current pose, published as an immutable LocalMap.
/// The first map comes from SGM (Initialize); Reset forgets everything so that the caller can
/// initialise again at the last good pose.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/observation.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/depth_fusion.hpp"
#include "aavio/mapping/local_map.hpp"
#include "aavio/mapping/mapping_config.hpp"
#include "aavio/mapping/temporal_partners.hpp"
#include "aavio/mapping/temporal_stereo.hpp"

namespace aavio::mapping {

/// A cycle with fewer usable edge samples maps nothing (the old map stays published): fewer than
/// a first map may have (BootstrapConfig::kMinRegistrationPoints). A sparse scene gives 80–130
/// samples a cycle, so a larger floor would leave it with its first map for good.
inline constexpr int kMinSamples = static_cast<int>(BootstrapConfig::kMinRegistrationPoints);
/// The edge samples a mapping cycle uses: the observation's, away from the border, at most
/// `max_points`, moved onto the newest edge (`snap_to_edge_px`).
std::vector<events::EdgeSample> MappingSamples(const events::Observation& obs,
                                               const RectifiedStereo& stereo,
                                               const MappingConfig& config);

/// Temporal points are matched and refined at their samples' own AA-map pixels, `matched_at`,
/// and join the map at the same samples snapped onto the newest edge, `snapped` (same order):
/// each temporal point of `points` (a subset of `matched_at`, in order, among static points
/// that stay where they are) moves to its sample's snapped position.
void MoveOntoNewestEdge(const std::vector<Eigen::Vector2f>& matched_at,
                        const std::vector<Eigen::Vector2f>& snapped,
                        std::vector<DepthPoint>* points);

struct MappingCycleReport {
  int samples = 0;  ///< edge samples considered (after the cap and the border)
  int static_candidates = 0, temporal_candidates = 0;
  int static_matches = 0, temporal_matches = 0;
  int static_points = 0, temporal_points = 0;  ///< after refinement and culling
  /// What became of the temporal candidates (matched + the rest = temporal_candidates).
  TemporalMatchStats temporal;
  int map_points = 0;
  /// Cycles whose static batch the fused map holds (the FIFO's length, the bootstrap included).
  int fused_cycles = 0;
  bool has_partner = false;
  /// The fused map replaced the published one (LocalMap::confirmed: also a depth output).
  bool published = false;
  double matching_ms = 0.0, refinement_ms = 0.0, fusion_ms = 0.0, total_ms = 0.0;
};

class Mapper {
 public:
  Mapper(const RectifiedStereo& stereo, const cv::Mat& valid_mask, const MappingConfig& config);

  bool initialized() const { return initialized_; }
  /// SGM on the observation's TS pair at its pose; FailedPrecondition if too few points.
  /// `small_map_ok` false refuses maps under `bootstrap.min_points` whatever their coverage
  /// (the odometry's choice while the IMU does not show the camera moving: a still camera's
  /// noise can give a small map).
  Status Initialize(const PosedObservation& now, bool small_map_ok = true);
  /// A mapping cycle; `partner` may be null (no temporal stereo this cycle), `check` is the
  /// cross-check partner (null: temporal matches are kept unchecked).
  Status Update(const PosedObservation& now, const PosedObservation* partner,
                MappingCycleReport* report, const PosedObservation* check = nullptr);
  /// Forgets the map (the temporal partners are the caller's: TemporalHistory).
  void Reset();

  LocalMapPtr local_map() const { return local_map_; }

 private:
  /// The first map's points, or why there are too few.
  Expected<std::vector<DepthPoint>> Bootstrap(const events::Observation& obs) const;
  /// bootstrap.method = block_matching: the cycle's static stereo and refinement at `positions`.
  std::vector<DepthPoint> BlockMatchingBootstrap(
      const events::Observation& obs, const std::vector<Eigen::Vector2f>& positions) const;
  void Publish(const DepthMap& map, bool confirmed);
  /// A cycle's refined points into the fusion FIFO (a batch per kind), a new map fused at the
  /// current pose, and published if the FIFO says so.
  void FuseCycle(const PosedObservation& now, const std::vector<DepthPoint>& refined,
                 MappingCycleReport* report);

  RectifiedStereo stereo_;
  cv::Mat valid_mask_;
  MappingConfig config_;
  DepthFusion fusion_;
  bool initialized_ = false;
  LocalMapPtr local_map_;
};

}  // namespace aavio::mapping
