#include "aavio/sim/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace aavio::sim {

double Quad::RadianceAt(double t_s) const {
  if (flicker_hz <= 0.0) return 1.0;
  const double phase = 2.0 * M_PI * flicker_hz * t_s + flicker_phase_rad;
  return 1.0 - flicker_depth * 0.5 * (1.0 + std::cos(phase));
}

void Scene::AddQuad(const Quad& quad) {
  quads_.push_back(quad);
}

void Scene::AddBox(const geometry::RigidTransform& T, const Eigen::Vector3d& size,
                   const std::vector<Texture>& textures, bool with_bottom,
                   const Eigen::Vector3d& velocity_mps) {
  const Eigen::Vector3d h = size / 2.0;
  const Eigen::Matrix3d& R = T.R;
  const Eigen::Vector3d ex = R.col(0) * size.x(), ey = R.col(1) * size.y(),
                        ez = R.col(2) * size.z();
  const Eigen::Vector3d corner = T * Eigen::Vector3d(-h.x(), -h.y(), -h.z());
  // Six faces: (origin, edge_u, edge_v); the texture's v runs "up" (+z) on the side faces.
  std::vector<std::array<Eigen::Vector3d, 3>> faces = {{corner, ex, ez},
                                                       {corner + ey, ex, ez},
                                                       {corner, ey, ez},
                                                       {corner + ex, ey, ez},
                                                       {corner + ez, ex, ey}};
  if (with_bottom) faces.push_back({corner, ex, ey});
  std::size_t k = 0;
  for (const auto& f : faces) {
    Quad q{f[0], f[1], f[2], textures.empty() ? Texture{} : textures[k++ % textures.size()]};
    q.texture.seed += k;
    q.velocity_mps = velocity_mps;
    AddQuad(q);
  }
}

void Scene::Transform(const geometry::RigidTransform& T) {
  for (Quad& q : quads_) {
    q.origin = T * q.origin;
    q.edge_u = T.R * q.edge_u;
    q.edge_v = T.R * q.edge_v;
    q.velocity_mps = T.R * q.velocity_mps;
  }
  Build();
}

void Scene::ScaleContrast(double factor) {
  for (Quad& q : quads_)
    q.texture.contrast *= factor;
}

void Scene::Build() {
  for (Quad& q : quads_)
    q.texture.Prepare();
  const std::size_t n = quads_.size();
  lo_.resize(n);
  hi_.resize(n);
  centre_.resize(n);
  order_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Quad& q = quads_[i];
    const Eigen::Vector3d corners[4] = {q.origin, q.origin + q.edge_u, q.origin + q.edge_v,
                                        q.origin + q.edge_u + q.edge_v};
    lo_[i] = hi_[i] = corners[0];
    for (const Eigen::Vector3d& c : corners) {
      lo_[i] = lo_[i].cwiseMin(c);
      hi_[i] = hi_[i].cwiseMax(c);
    }
    centre_[i] = (lo_[i] + hi_[i]) / 2.0;
    order_[i] = static_cast<std::uint32_t>(i);
  }
  nodes_.clear();
  nodes_.reserve(2 * n + 1);
  if (n > 0) BuildNode(0, static_cast<std::uint32_t>(n));
}

std::uint32_t Scene::BuildNode(std::uint32_t first, std::uint32_t count) {
  const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  Node node;
  node.lo = lo_[order_[first]];
  node.hi = hi_[order_[first]];
  Eigen::Vector3d c_lo = centre_[order_[first]], c_hi = c_lo;
  for (std::uint32_t k = first; k < first + count; ++k) {
    node.lo = node.lo.cwiseMin(lo_[order_[k]]);
    node.hi = node.hi.cwiseMax(hi_[order_[k]]);
    c_lo = c_lo.cwiseMin(centre_[order_[k]]);
    c_hi = c_hi.cwiseMax(centre_[order_[k]]);
  }
  if (count <= 4) {
    node.first = first;
    node.count = count;
  } else {
    int axis = 0;
    (c_hi - c_lo).maxCoeff(&axis);
    const std::uint32_t mid = first + count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return centre_[a][axis] < centre_[b][axis] ||
                              (centre_[a][axis] == centre_[b][axis] && a < b);
                     });
    node.left = BuildNode(first, mid - first);
    node.right = BuildNode(mid, first + count - mid);
  }
  nodes_[index] = node;
  return index;
}

bool Scene::IntersectQuad(std::uint32_t index, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                          Hit* hit) const {
  const Quad& q = quads_[index];
  const Eigen::Vector3d normal = q.edge_u.cross(q.edge_v);
  const double denom = normal.dot(dir);
  if (std::abs(denom) < 1e-12) return false;
  const double s = normal.dot(q.origin - o) / denom;
  if (s <= 1e-6 || s >= hit->distance) return false;
  const Eigen::Vector3d p = o + s * dir - q.origin;
  const double uu = q.edge_u.squaredNorm(), vv = q.edge_v.squaredNorm();
  const double a = p.dot(q.edge_u) / uu, b = p.dot(q.edge_v) / vv;
  if (a < 0.0 || a > 1.0 || b < 0.0 || b > 1.0) return false;
  hit->distance = s;
  hit->quad = index;
  hit->u_m = a * std::sqrt(uu);
  hit->v_m = b * std::sqrt(vv);
  hit->cos_incidence = std::abs(denom) / normal.norm();
  return true;
}

bool Scene::Intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& dir, Hit* hit) const {
  if (nodes_.empty()) return false;
  hit->distance = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d inv(1.0 / dir.x(), 1.0 / dir.y(), 1.0 / dir.z());
  auto box_entry = [&](const Node& n) {
    const Eigen::Vector3d t0 = (n.lo - o).cwiseProduct(inv), t1 = (n.hi - o).cwiseProduct(inv);
    const double near = t0.cwiseMin(t1).maxCoeff(), far = t0.cwiseMax(t1).minCoeff();
    return (far >= std::max(near, 0.0) && near < hit->distance)
               ? std::max(near, 0.0)
               : std::numeric_limits<double>::infinity();
  };
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  bool found = false;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!std::isfinite(box_entry(n))) continue;
    if (n.count > 0) {
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
        found |= IntersectQuad(order_[k], o, dir, hit);
      continue;
    }
    // Visit the nearer child first.
    const double dl = box_entry(nodes_[n.left]), dr = box_entry(nodes_[n.right]);
    if (dl < dr) {
      if (std::isfinite(dr)) stack[top++] = n.right;
      stack[top++] = n.left;
    } else {
      if (std::isfinite(dl)) stack[top++] = n.left;
      if (std::isfinite(dr)) stack[top++] = n.right;
    }
  }
  return found;
}

}  // namespace aavio::sim
