#include "aavio/mapping/global_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace aavio::mapping {

GlobalCloud::GlobalCloud(double voxel_m) : voxel_m_(voxel_m) {}

std::size_t GlobalCloud::VoxelSet::Home(std::uint64_t key) const {
  // splitmix64's finaliser: neighbouring voxels land far apart.
  key ^= key >> 30;
  key *= 0xbf58476d1ce4e5b9ULL;
  key ^= key >> 27;
  key *= 0x94d049bb133111ebULL;
  key ^= key >> 31;
  return static_cast<std::size_t>(key) & (slots_.size() - 1);
}

bool GlobalCloud::VoxelSet::Contains(std::uint64_t key) const {
  for (std::size_t i = Home(key);; i = (i + 1) & (slots_.size() - 1)) {
    if (slots_[i] == 0) return false;
    if (slots_[i] == key + 1) return true;
  }
}

void GlobalCloud::VoxelSet::Insert(std::uint64_t key) {
  std::size_t i = Home(key);
  while (slots_[i] != 0)
    i = (i + 1) & (slots_.size() - 1);
  slots_[i] = key + 1;
  ++size_;
}

void GlobalCloud::VoxelSet::Clear() {
  std::fill(slots_.begin(), slots_.end(), 0);
  size_ = 0;
}

bool GlobalCloud::Visit(std::uint64_t key) {
  if (current_.Contains(key)) return false;
  const bool seen = previous_.Contains(key);
  if (current_.size() == kGeneration) {  // a new generation; the oldest is forgotten
    std::swap(current_, previous_);
    current_.Clear();
  }
  current_.Insert(key);
  return !seen;
}

void GlobalCloud::Add(const LocalMap& map, double max_depth_m, std::vector<CloudPoint>* added) {
  // 21 bits per axis around the origin: ±1e6 voxels.
  auto cell = [&](double x) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x / voxel_m_)) +
                                      (1 << 20)) &
           0x1fffff;
  };
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    if (1.0 / map.points[i].rho > max_depth_m) continue;
    const Eigen::Vector3d& p = map.points_world[i];
    if (!Visit(cell(p.x()) << 42 | cell(p.y()) << 21 | cell(p.z()))) continue;
    added->push_back({p.cast<float>(), static_cast<float>(map.points[i].rho)});
    ++size_;
  }
}

}  // namespace aavio::mapping
