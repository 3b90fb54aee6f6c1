#pragma once
/// The simulator's world: textured rectangles ("quads") — walls, floors, facades, box faces —
/// in a bounding-volume hierarchy for ray casting.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/sim/texture.hpp"

namespace aavio::sim {

/// origin + s·edge_u + t·edge_v for s, t in [0, 1]; the edges are perpendicular. Texture
/// coordinates are metres along the edges from the origin.
///
/// Two world effects live on quads: a moving object's faces translate with `velocity_mps` (the
/// origin is where they are at Scene::time_origin_ns), and a light source's radiance flickers:
/// its albedo times 1 − depth · (1 + cos(2π f t + φ)) / 2, between (1 − depth) and 1 of it.
struct Quad {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d edge_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d edge_v = Eigen::Vector3d::UnitY();
  Texture texture;
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();  ///< world frame; 0 = static
  double flicker_hz = 0.0;                                 ///< 0 = steady
  double flicker_depth = 0.0;                              ///< in [0, 1)
  double flicker_phase_rad = 0.0;

  bool moves() const { return !velocity_mps.isZero(); }
  /// Where the origin is at `t_s` seconds after the scene's time origin.
  Eigen::Vector3d OriginAt(double t_s) const { return origin + velocity_mps * t_s; }
  /// The radiance factor at `t_s` seconds after the scene's time origin (1 when steady).
  double RadianceAt(double t_s) const;
};

struct Hit {
  double distance = 0.0;  ///< along the (unit) ray [m]
  std::uint32_t quad = 0;
  double u_m = 0.0, v_m = 0.0;  ///< texture coordinates
  double cos_incidence = 1.0;   ///< |cos| of the angle between ray and surface normal
};

class Scene {
 public:
  void AddQuad(const Quad& quad);
  /// A box of size (x, y, z) [m] centred at T_world_box's origin; `textures` are used in turn
  /// for its faces; `with_bottom` false leaves out the face at −z (boxes standing on a floor);
  /// a moving box's faces share `velocity_mps`.
  void AddBox(const geometry::RigidTransform& T_world_box, const Eigen::Vector3d& size,
              const std::vector<Texture>& textures, bool with_bottom = true,
              const Eigen::Vector3d& velocity_mps = Eigen::Vector3d::Zero());
  /// Builds the BVH; call after the last Add and before Intersect.
  void Build();
  /// Moves every quad by T_new_old (p_new = T · p_old) and rebuilds the BVH.
  void Transform(const geometry::RigidTransform& T_new_old);
  /// Every texture's contrast (the spread of its albedos) times `factor`: fainter or bolder
  /// patterns on the same geometry.
  void ScaleContrast(double factor);

  /// Nearest hit of the ray o + s·dir (dir of unit length, s > 1e-6); false if none. Moving
  /// quads are where they are at the time origin.
  bool Intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& dir, Hit* hit) const;

  const std::vector<Quad>& quads() const { return quads_; }
  double sky_albedo = 0.45;   ///< what rays that hit nothing see
  TimeNs time_origin_ns = 0;  ///< the time moving quads' origins and flicker phases refer to

 private:
  struct Node {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero();
    Eigen::Vector3d hi = Eigen::Vector3d::Zero();
    std::uint32_t first = 0, count = 0;  // leaf: quads order_[first, first + count)
    std::uint32_t left = 0, right = 0;   // inner node (count == 0)
  };
  std::uint32_t BuildNode(std::uint32_t first, std::uint32_t count);
  bool IntersectQuad(std::uint32_t index, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                     Hit* hit) const;

  std::vector<Quad> quads_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
  std::vector<Eigen::Vector3d> lo_, hi_, centre_;  // per-quad bounds
};

}  // namespace aavio::sim
