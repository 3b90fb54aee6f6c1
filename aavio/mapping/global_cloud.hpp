#pragma once
/// The global point cloud for output (map.ply): local maps' points accumulated on a voxel grid,
/// one point per voxel (the first to arrive), in arrival order — deterministic.

#include <Eigen/Core>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "aavio/mapping/local_map.hpp"

namespace aavio::mapping {

class GlobalCloud {
 public:
  explicit GlobalCloud(double voxel_m) : voxel_m_(voxel_m) {}
  /// Adds the points of a local map closer than max_depth_m to its frame.
  void Add(const LocalMap& map, double max_depth_m);
  const std::vector<Eigen::Vector3f>& points() const { return points_; }
  const std::vector<float>& inv_depth() const { return inv_depth_; }

 private:
  double voxel_m_;
  std::unordered_set<std::uint64_t> occupied_;
  std::vector<Eigen::Vector3f> points_;
  std::vector<float> inv_depth_;  // at insertion, for colouring
};

}  // namespace aavio::mapping
