#pragma once
/// The FIFO of recent depth batches and their fusion into a fresh depth map at every mapping
/// cycle (docs/mapping.md). Static and temporal batches have FIFOs of their own and are
/// both always fused (ESVO2's rpg configuration silently drops temporal results); static batches
/// first, newest first, then cleaning once the FIFO is full, then temporal batches.

#include <deque>
#include <vector>

#include "aavio/mapping/depth_map.hpp"

namespace aavio::mapping {

struct DepthBatch {
  TimeNs t_ns = 0;
  geometry::RigidTransform T_world_obs;
  std::vector<DepthPoint> points;
};

/// How a full FIFO's fused map is cleaned (docs/mapping.md).
struct MapCleaning {
  double max_inv_depth_stddev = 1.0;  ///< depth_refinement's: a fused point's σ_ρ above it goes
  InvDepthRange range;                ///< points outside it go
  bool regularize = false;            ///< regularization.enabled
};

class DepthFusion {
 public:
  DepthFusion(const RectifiedStereo& stereo, const FusionConfig& fusion,
              const MapCleaning& cleaning);

  void Add(StereoKind kind, DepthBatch batch);
  /// A new map at T_world_frame with every stored batch propagated and fused into it.
  DepthMap Fuse(const geometry::RigidTransform& T_world_frame, TimeNs t_ns) const;
  /// Forgets every batch (re-initialisation).
  void Clear();

  /// Cleaning starts: const_frames, max_frames batches; const_points, max_points points.
  bool full() const;
  /// A fused map is worth publishing (docs/mapping.md): const_frames, the FIFO is full;
  /// const_points, it holds more than half of max_points.
  bool ready_to_publish() const;
  std::size_t batches() const { return static_.size() + temporal_.size(); }
  /// Static batches stored: one per mapping cycle the map holds (and the bootstrap's).
  std::size_t static_batches() const { return static_.size(); }
  std::size_t stored_points() const;

 private:
  void Trim(std::deque<DepthBatch>* fifo) const;

  RectifiedStereo stereo_;
  FusionConfig config_;
  MapCleaning cleaning_;
  std::deque<DepthBatch> static_, temporal_;  // newest at the back
};

}  // namespace aavio::mapping
