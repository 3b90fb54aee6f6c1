#include "aavio/mapping/depth_map.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace aavio::mapping {

DepthPoint FuseStudentT(const DepthPoint& a, const DepthPoint& b) {
  DepthPoint f = a;
  const double nu = std::min(a.nu, b.nu);
  const double sum = a.s2 + b.s2;
  const double d = a.rho - b.rho;
  f.rho = (b.s2 * a.rho + a.s2 * b.rho) / sum;
  f.s2 = (nu + d * d / sum) / (nu + 1.0) * (a.s2 * b.s2 / sum);
  f.nu = nu + 1.0;
  f.age = std::max(a.age, b.age) + 1;
  f.residual = std::min(a.residual, b.residual);
  f.near_horizontal = a.near_horizontal || b.near_horizontal;
  return f;
}

bool Compatible(const DepthPoint& a, const DepthPoint& b, double sigmas) {
  const double d = std::abs(a.rho - b.rho);
  return d < sigmas * std::sqrt(a.variance()) || d < sigmas * std::sqrt(b.variance());
}

bool Propagate(const DepthPoint& point, const geometry::RigidTransform& T_f_o,
               const RectifiedStereo& stereo, DepthPoint* out) {
  const double pu = point.u, pv = point.v;
  const Eigen::Vector3d bar((pu - stereo.cx_left) / stereo.f, (pv - stereo.cy) / stereo.f, 1.0);
  const Eigen::Vector3d p = T_f_o * (bar / point.rho);
  double u, v;
  if (!stereo.Project(p, &u, &v)) return false;
  if (u < 0.0 || v < 0.0 || u > stereo.width - 1.0 || v > stereo.height - 1.0) return false;
  const double r3x = T_f_o.R.row(2).dot(bar);
  const double denominator = r3x + T_f_o.t.z() * point.rho;
  const double J = r3x / (denominator * denominator);
  *out = point;
  out->u = static_cast<float>(u);
  out->v = static_cast<float>(v);
  out->rho = 1.0 / p.z();
  out->s2 = J * J * point.s2;
  return true;
}

DepthMap::DepthMap(const RectifiedStereo& stereo, const geometry::RigidTransform& T_world_frame,
                   TimeNs t_ns)
    : stereo_(stereo),
      T_world_frame_(T_world_frame),
      t_ns_(t_ns),
      index_(static_cast<std::size_t>(stereo.width) * static_cast<std::size_t>(stereo.height), -1) {
}

const DepthPoint* DepthMap::At(int x, int y) const {
  const std::int32_t slot = index_[static_cast<std::size_t>(y) * stereo_.width + x];
  return slot < 0 ? nullptr : &points_[static_cast<std::size_t>(slot)];
}

void DepthMap::Place(int x, int y, const DepthPoint& point) {
  const std::size_t cell = static_cast<std::size_t>(y) * stereo_.width + x;
  std::int32_t& slot = index_[cell];
  if (slot < 0) {
    slot = static_cast<std::int32_t>(points_.size());
    points_.push_back(point);
    cell_of_.push_back(static_cast<std::int32_t>(cell));
    ++occupied_;
  } else {
    points_[static_cast<std::size_t>(slot)] = point;
  }
  DepthPoint& stored = points_[static_cast<std::size_t>(slot)];
  stored.u = static_cast<float>(x);  // snapped to the cell; the 3-D point follows from (u, v, ρ)
  stored.v = static_cast<float>(y);
}

void DepthMap::Remove(std::int32_t slot) {
  index_[static_cast<std::size_t>(cell_of_[static_cast<std::size_t>(slot)])] = -1;
  --occupied_;
}

void DepthMap::FuseCell(int x, int y, const DepthPoint& point, const FusionConfig& config) {
  const DepthPoint* cell = At(x, y);
  if (cell == nullptr) {
    Place(x, y, point);
    return;
  }
  if (Compatible(*cell, point, config.compatibility_sigmas)) {
    const DepthPoint fused = FuseStudentT(*cell, point);
    Place(x, y, fused);
    return;
  }
  // Occlusion: a clearly closer stored point stays; otherwise the new one replaces it only if
  // it is better in both variance and residual.
  if (cell->rho - config.compatibility_sigmas * std::sqrt(cell->variance()) > point.rho) return;
  if (point.variance() < cell->variance() && point.residual < cell->residual) Place(x, y, point);
}

void DepthMap::Fuse(const DepthPoint& point, const FusionConfig& config) {
  const int x0 = static_cast<int>(std::floor(point.u)), y0 = static_cast<int>(std::floor(point.v));
  const int lo = config.radius == 0 ? 0 : -1, hi = 1;
  for (int dy = lo; dy <= hi; ++dy) {
    for (int dx = lo; dx <= hi; ++dx) {
      const int x = x0 + dx, y = y0 + dy;
      if (x < 0 || y < 0 || x >= stereo_.width || y >= stereo_.height) continue;
      FuseCell(x, y, point, config);
    }
  }
}

void DepthMap::InsertNaive(const DepthPoint& point) {
  const int x0 = static_cast<int>(std::floor(point.u)), y0 = static_cast<int>(std::floor(point.v));
  for (int dy = 0; dy <= 1; ++dy) {
    for (int dx = 0; dx <= 1; ++dx) {
      const int x = x0 + dx, y = y0 + dy;
      if (x < 0 || y < 0 || x >= stereo_.width || y >= stereo_.height) continue;
      const DepthPoint* stored = At(x, y);
      if (stored == nullptr || (stored->rho <= point.rho && point.residual < stored->residual)) {
        Place(x, y, point);
      }
    }
  }
}

void DepthMap::Clean(double max_stddev, int min_age, double rho_lo, double rho_hi) {
  for (std::size_t slot = 0; slot < points_.size(); ++slot) {
    if (!Live(slot)) continue;
    const DepthPoint& p = points_[slot];
    if (std::sqrt(p.variance()) > max_stddev || p.age < min_age || p.rho < rho_lo ||
        p.rho > rho_hi) {
      Remove(static_cast<std::int32_t>(slot));
    }
  }
}

void DepthMap::Regularize(const RegularizationConfig& config, double compatibility_sigmas) {
  // Every point reads its neighbours from the map as it was before this pass: the new depths and
  // the removals are collected (points in parallel) and applied afterwards, in slot order.
  const std::size_t n = points_.size();
  const int w = stereo_.width, h = stereo_.height, r = config.radius;
  // Compatible(p, q) = |ρp − ρq| < k·σp or < k·σq: each point's k·σ once, not per pair.
  std::vector<double> reach(n, 0.0);
  for (std::size_t slot = 0; slot < n; ++slot)
    if (Live(slot)) reach[slot] = compatibility_sigmas * std::sqrt(points_[slot].variance());
  enum : char { kKeep, kFused, kRemove };
  std::vector<char> outcome(n, kKeep);
  std::vector<double> fused_rho(n, 0.0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 256),
      [&](const tbb::blocked_range<std::size_t>& range) {
        std::vector<const DepthPoint*> close;
        for (std::size_t slot = range.begin(); slot != range.end(); ++slot) {
          if (!Live(slot)) continue;
          const DepthPoint& p = points_[slot];
          const int x = cell_of_[slot] % w, y = cell_of_[slot] / w;
          int neighbours = 0;
          close.clear();
          for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy) {
            const std::int32_t* row = index_.data() + static_cast<std::size_t>(yy) * w;
            for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
              const std::int32_t q_slot = row[xx];
              if (q_slot < 0 || (xx == x && yy == y)) continue;
              const DepthPoint& q = points_[static_cast<std::size_t>(q_slot)];
              ++neighbours;
              const double d = std::abs(p.rho - q.rho);
              if (d < reach[slot] || d < reach[static_cast<std::size_t>(q_slot)])
                close.push_back(&q);
            }
          }
          if (neighbours <= config.min_neighbours) continue;
          if (static_cast<int>(close.size()) <= config.min_close_neighbours) {
            outcome[slot] = kRemove;  // an outlier among many neighbours
            continue;
          }
          // FuseStudentT over the compatible neighbours, keeping only what ρ depends on.
          double rho = p.rho, s2 = p.s2, nu = p.nu;
          for (const DepthPoint* q : close) {
            const double sum = s2 + q->s2, d = rho - q->rho, nu_min = std::min(nu, q->nu);
            rho = (q->s2 * rho + s2 * q->rho) / sum;
            s2 = (nu_min + d * d / sum) / (nu_min + 1.0) * (s2 * q->s2 / sum);
            nu = nu_min + 1.0;
          }
          outcome[slot] = kFused;
          fused_rho[slot] = rho;
        }
      });
  for (std::size_t slot = 0; slot < n; ++slot) {
    if (outcome[slot] == kRemove)
      Remove(static_cast<std::int32_t>(slot));
    else if (outcome[slot] == kFused)
      points_[slot].rho = fused_rho[slot];
  }
}

std::vector<DepthPoint> DepthMap::Points() const {
  std::vector<DepthPoint> points;
  points.reserve(occupied_);
  for (std::size_t slot = 0; slot < points_.size(); ++slot) {
    if (Live(slot)) points.push_back(points_[slot]);
  }
  return points;
}

std::size_t DepthMap::size() const {
  return occupied_;
}

}  // namespace aavio::mapping
