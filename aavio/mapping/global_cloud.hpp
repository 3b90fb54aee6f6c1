#pragma once
/// The global point cloud (map.ply): which points of the confirmed local maps are new to it.
/// Space is cut into voxels and a voxel takes the first point that lands in it, in arrival order
/// (deterministic). The points are handed on as they come (the run recorder streams them to
/// map.ply), not kept, and the voxels remembered are the most recently filled ones, at most
/// 2 × kGeneration (8 MB): memory stays flat however long the run. A voxel forgotten (more than
/// ~260 000 newer voxels since it was last hit) and revisited gets a second point.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "aavio/mapping/local_map.hpp"

namespace aavio::mapping {

struct CloudPoint {
  Eigen::Vector3f p_world;
  float inv_depth = 0.f;  ///< in its local map's frame (for colouring)
};

class GlobalCloud {
 public:
  /// Voxels remembered per generation; two generations are kept.
  static constexpr std::size_t kGeneration = std::size_t{1} << 18;

  explicit GlobalCloud(double voxel_m);
  /// Appends to `added` the points of `map` closer than max_depth_m to its frame whose voxel is
  /// empty.
  void Add(const LocalMap& map, double max_depth_m, std::vector<CloudPoint>* added);
  /// Points added so far.
  std::size_t size() const { return size_; }

 private:
  /// A fixed-size open-addressing set of voxel keys (linear probing, load ≤ 1/2).
  class VoxelSet {
   public:
    VoxelSet() : slots_(2 * kGeneration, 0) {}
    bool Contains(std::uint64_t key) const;
    void Insert(std::uint64_t key);  ///< key not yet in; at most kGeneration keys
    void Clear();
    std::size_t size() const { return size_; }

   private:
    std::size_t Home(std::uint64_t key) const;
    std::vector<std::uint64_t> slots_;  ///< key + 1; 0 = empty
    std::size_t size_ = 0;
  };
  /// Whether the voxel is new; remembers it in any case.
  bool Visit(std::uint64_t key);

  double voxel_m_;
  VoxelSet current_, previous_;
  std::size_t size_ = 0;
};

}  // namespace aavio::mapping
