#include "aavio/mapping/depth_fusion.hpp"

namespace aavio::mapping {

DepthFusion::DepthFusion(const RectifiedStereo& stereo, const FusionConfig& fusion,
                         const MapCleaning& cleaning)
    : stereo_(stereo), config_(fusion), cleaning_(cleaning) {}

std::size_t DepthFusion::stored_points() const {
  std::size_t n = 0;
  for (const auto* fifo : {&static_, &temporal_}) {
    for (const DepthBatch& b : *fifo)
      n += b.points.size();
  }
  return n;
}

void DepthFusion::Trim(std::deque<DepthBatch>* fifo) const {
  const FusionConfig& f = config_;
  if (f.strategy == FusionStrategy::kConstFrames) {
    while (static_cast<int>(fifo->size()) > f.max_frames)
      fifo->pop_front();
    return;
  }
  auto points = [&] {
    std::size_t n = 0;
    for (const DepthBatch& b : *fifo)
      n += b.points.size();
    return n;
  };
  while (fifo->size() > 1 && static_cast<double>(points()) > 1.5 * f.max_points)
    fifo->pop_front();
}

void DepthFusion::Add(StereoKind kind, DepthBatch batch) {
  std::deque<DepthBatch>& fifo = kind == StereoKind::kStatic ? static_ : temporal_;
  fifo.push_back(std::move(batch));
  Trim(&fifo);
}

bool DepthFusion::full() const {
  // const_frames: max_frames batches; const_points: the point budget is reached, or (aavio)
  // max_frames batches where the scene gives too few points to reach it. (The reference tests
  // the frame count for both, so with const_points and small batches it never cleans.)
  const bool frames = static_cast<int>(static_.size()) >= config_.max_frames;
  if (config_.strategy == FusionStrategy::kConstFrames) return frames;
  if (config_.full_at_max_frames && frames) return true;
  std::size_t points = 0;
  for (const DepthBatch& b : static_)
    points += b.points.size();
  return static_cast<double>(points) >= config_.max_points;
}

bool DepthFusion::ready_to_publish() const {
  if (config_.strategy == FusionStrategy::kConstFrames || full()) return full();
  std::size_t points = 0;
  for (const DepthBatch& b : static_)
    points += b.points.size();
  return static_cast<double>(points) > 0.5 * config_.max_points;
}

void DepthFusion::Clear() {
  static_.clear();
  temporal_.clear();
}

DepthMap DepthFusion::Fuse(const geometry::RigidTransform& T_world_frame, TimeNs t_ns) const {
  DepthMap map(stereo_, T_world_frame, t_ns);
  const geometry::RigidTransform T_frame_world = T_world_frame.Inverse();
  int batch_id = 0;
  auto fuse_fifo = [&](const std::deque<DepthBatch>& fifo) {
    for (auto batch = fifo.rbegin(); batch != fifo.rend(); ++batch, ++batch_id) {
      const geometry::RigidTransform T_f_o = T_frame_world * batch->T_world_obs;
      DepthPoint moved;
      for (const DepthPoint& p : batch->points) {
        if (!Propagate(p, T_f_o, stereo_, &moved)) continue;
        moved.batch = batch_id;
        map.Fuse(moved, config_);
      }
    }
  };
  auto clean = [&] {
    if (!full()) return;
    map.Clean(cleaning_.max_inv_depth_stddev, cleaning_.range.min, cleaning_.range.max);
    if (cleaning_.regularize) map.Regularize();
  };
  fuse_fifo(static_);
  // Temporal points are fused before cleaning, so they need confirmation like static ones
  // (aavio; ESVO2 adds them after cleaning and never cleans them).
  fuse_fifo(temporal_);
  clean();
  return map;
}

}  // namespace aavio::mapping
