#pragma once
/// The semi-dense inverse-depth map of one frame (docs/mapping.md): a grid of cells, each
/// empty or holding one DepthPoint, and the Student-t fusion rules that fill it.

#include <cstdint>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/depth_point.hpp"
#include "aavio/mapping/mapping_config.hpp"

namespace aavio::mapping {

/// Two estimates within this many σ (of either) are of the same surface ([ESVO]).
inline constexpr double kCompatibilitySigmas = 2.0;
/// Fusions a point needs to survive cleaning ([ESVO], [ICRA code]).
inline constexpr int kMinAge = 1;

class DepthMap {
 public:
  DepthMap(const RectifiedStereo& stereo, const geometry::RigidTransform& T_world_frame,
           TimeNs t_ns);

  /// Fuses a point already expressed in this frame into its neighbourhood of cells (2×2 for
  /// radius 0, else 3×3): empty cells take a copy, compatible ones (|Δρ| < 2σ of either) are
  /// fused (Student-t), incompatible ones follow the occlusion rule.
  void Fuse(const DepthPoint& point, const FusionConfig& config);
  /// Inserts into the 2×2 cells without fusing: on conflict keeps the closer stored point,
  /// otherwise replaces it if the new one has a smaller residual (the SGM bootstrap, §4.12).
  void InsertNaive(const DepthPoint& point);
  /// Removes points with σ_ρ above max_stddev, age below kMinAge, or ρ outside [lo, hi].
  void Clean(double max_stddev, double rho_lo, double rho_hi);
  /// Neighbourhood regularisation (§4.10, [ESVO] rpg): a point with more than 8 neighbours within
  /// 5 cells is removed when at most 8 of them are compatible, else fused with those.
  void Regularize();

  /// The occupied cells' points (in the order their cells were first filled: deterministic).
  std::vector<DepthPoint> Points() const;
  std::size_t size() const;
  const geometry::RigidTransform& T_world_frame() const { return T_world_frame_; }
  TimeNs t_ns() const { return t_ns_; }
  const RectifiedStereo& stereo() const { return stereo_; }
  const DepthPoint* At(int x, int y) const;

 private:
  void FuseCell(int x, int y, const DepthPoint& point, const FusionConfig& config);
  void Place(int x, int y, const DepthPoint& point);
  void Remove(std::int32_t slot);
  bool Live(std::size_t slot) const {
    return index_[static_cast<std::size_t>(cell_of_[slot])] == static_cast<std::int32_t>(slot);
  }

  RectifiedStereo stereo_;
  geometry::RigidTransform T_world_frame_;
  TimeNs t_ns_;
  // A grid of slot indices (−1: empty cell) into the points; removed slots stay as holes.
  std::vector<std::int32_t> index_;
  std::vector<DepthPoint> points_;
  std::vector<std::int32_t> cell_of_;  // per slot
  std::size_t occupied_ = 0;
};

/// Student-t fusion of two estimates of the same surface (docs/mapping.md).
DepthPoint FuseStudentT(const DepthPoint& a, const DepthPoint& b);
bool Compatible(const DepthPoint& a, const DepthPoint& b, double sigmas);

/// A point of frame `o` expressed in frame `f` (T_f_o = T_world_f⁻¹ T_world_o): new position and
/// ρ' = 1/z', scale² through the exact inverse-depth Jacobian ∂ρ'/∂ρ = (r₃·x̄)/(r₃·x̄ + t₃ρ)²
/// with x̄ = (x̄, ȳ, 1). False if it leaves the image or goes behind the camera.
bool Propagate(const DepthPoint& point, const geometry::RigidTransform& T_f_o,
               const RectifiedStereo& stereo, DepthPoint* out);

}  // namespace aavio::mapping
