#include "aavio/mapping/depth_map.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
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
  f.batch = b.batch;
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
  if (Compatible(*cell, point, kCompatibilitySigmas)) {
    DepthPoint fused = FuseStudentT(*cell, point);
    // A neighbouring estimate of the same batch, splatted into a shared cell, is no independent
    // confirmation (confirm_across_batches).
    if (config.confirm_across_batches && point.batch >= 0 && cell->batch == point.batch)
      fused.age = std::max(cell->age, point.age);
    Place(x, y, fused);
    return;
  }
  // Occlusion: a clearly closer stored point stays; otherwise the new one replaces it only if
  // it is better in both variance and residual.
  if (cell->rho - kCompatibilitySigmas * std::sqrt(cell->variance()) > point.rho) return;
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

void DepthMap::Clean(double max_stddev, double rho_lo, double rho_hi) {
  for (std::size_t slot = 0; slot < points_.size(); ++slot) {
    if (!Live(slot)) continue;
    const DepthPoint& p = points_[slot];
    if (std::sqrt(p.variance()) > max_stddev || p.age < kMinAge || p.rho < rho_lo ||
        p.rho > rho_hi) {
      Remove(static_cast<std::int32_t>(slot));
    }
  }
}

namespace {

constexpr int kRegularizationRadius = 5, kMinNeighbours = 8, kMinCloseNeighbours = 8;

// The occupied cells of a w × h grid in row-major order, with one occupancy bitset per row: the
// occupied cells of a row between two columns are a contiguous run of ranks (found by popcounts),
// so a window is visited as 2r + 1 runs in the order of a row-major scan.
class CellRanks {
 public:
  CellRanks(int width, int height)
      : w_(width),
        words_((width + 63) / 64),
        occupied_(static_cast<std::size_t>(height) * words_) {}
  void Occupy(int x, int y) {
    occupied_[static_cast<std::size_t>(y) * words_ + (x >> 6)] |= std::uint64_t{1} << (x & 63);
  }
  // After the last Occupy: the number of occupied cells.
  std::size_t Index() {
    // before_word_[y·words + i]: occupied cells before word i of row y (all rows above included).
    before_word_.assign(occupied_.size() + 1, 0);
    for (std::size_t i = 0; i < occupied_.size(); ++i)
      before_word_[i + 1] = before_word_[i] + std::popcount(occupied_[i]);
    return static_cast<std::size_t>(before_word_.back());
  }
  // Rank of cell (x, y), x in [0, w]: the number of occupied cells before it in row-major order.
  std::int32_t Rank(int x, int y) const {
    const std::size_t word = static_cast<std::size_t>(y) * words_ + (x >> 6);
    if (x == w_) return before_word_[static_cast<std::size_t>(y + 1) * words_];
    const std::uint64_t below = (std::uint64_t{1} << (x & 63)) - 1;
    return before_word_[word] + std::popcount(occupied_[word] & below);
  }

 private:
  int w_, words_;
  std::vector<std::uint64_t> occupied_;
  std::vector<std::int32_t> before_word_;
};

// The live points in rank order, as columns.
struct PointColumns {
  explicit PointColumns(std::size_t n) : slot(n), x(n), y(n), rho(n), s2(n), nu(n), reach(n) {}
  std::vector<std::int32_t> slot, x, y;
  std::vector<double> rho, s2, nu;
  std::vector<double> reach;  // k·σ: Compatible(p, q) = |ρp − ρq| < reach p or reach q
};

enum RegularizationOutcome : char { kKeep, kFused, kRemove };

// Point i among its neighbours within the radius (as the map was before this pass): kept when
// they are few, removed when at most kMinCloseNeighbours are compatible, else fused with those
// (*fused_rho). `close` is scratch space.
RegularizationOutcome RegularizePoint(std::size_t i, const PointColumns& p, const CellRanks& ranks,
                                      int w, int h, std::vector<std::int32_t>* close,
                                      double* fused_rho) {
  const int r = kRegularizationRadius;
  const int x = p.x[i], y = p.y[i];
  const int x_lo = std::max(0, x - r), x_end = std::min(w, x + r + 1);
  int neighbours = -1;  // the point itself is in its own row's run
  close->clear();
  for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy) {
    const std::int32_t k_lo = ranks.Rank(x_lo, yy), k_end = ranks.Rank(x_end, yy);
    neighbours += k_end - k_lo;
    for (std::int32_t k = k_lo; k < k_end; ++k) {
      const double d = std::abs(p.rho[i] - p.rho[static_cast<std::size_t>(k)]);
      if ((d < p.reach[i] || d < p.reach[static_cast<std::size_t>(k)]) &&
          k != static_cast<std::int32_t>(i))
        close->push_back(k);
    }
  }
  if (neighbours <= kMinNeighbours) return kKeep;
  if (static_cast<int>(close->size()) <= kMinCloseNeighbours) return kRemove;  // an outlier
  // FuseStudentT over the compatible neighbours, keeping only what ρ depends on.
  double rho_f = p.rho[i], s2_f = p.s2[i], nu_f = p.nu[i];
  for (const std::int32_t k : *close) {
    const auto q = static_cast<std::size_t>(k);
    const double sum = s2_f + p.s2[q], d = rho_f - p.rho[q], nu_min = std::min(nu_f, p.nu[q]);
    rho_f = (p.s2[q] * rho_f + s2_f * p.rho[q]) / sum;
    s2_f = (nu_min + d * d / sum) / (nu_min + 1.0) * (s2_f * p.s2[q] / sum);
    nu_f = nu_min + 1.0;
  }
  *fused_rho = rho_f;
  return kFused;
}

}  // namespace

void DepthMap::Regularize() {
  // Every point reads its neighbours from the map as it was before this pass: the new depths and
  // the removals are collected (points in parallel) and applied afterwards.
  const int w = stereo_.width, h = stereo_.height;
  CellRanks ranks(w, h);
  for (std::size_t slot = 0; slot < points_.size(); ++slot)
    if (Live(slot)) ranks.Occupy(cell_of_[slot] % w, cell_of_[slot] / w);
  const std::size_t n = ranks.Index();
  PointColumns columns(n);
  for (std::size_t slot = 0; slot < points_.size(); ++slot) {
    if (!Live(slot)) continue;
    const int x = cell_of_[slot] % w, y = cell_of_[slot] / w;
    const auto k = static_cast<std::size_t>(ranks.Rank(x, y));
    const DepthPoint& p = points_[slot];
    columns.slot[k] = static_cast<std::int32_t>(slot);
    columns.x[k] = x;
    columns.y[k] = y;
    columns.rho[k] = p.rho;
    columns.s2[k] = p.s2;
    columns.nu[k] = p.nu;
    columns.reach[k] = kCompatibilitySigmas * std::sqrt(p.variance());
  }
  std::vector<RegularizationOutcome> outcome(n, kKeep);
  std::vector<double> fused_rho(n, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<std::int32_t> close;
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        outcome[i] =
                            RegularizePoint(i, columns, ranks, w, h, &close, &fused_rho[i]);
                    });
  // Applied afterwards (removals and new depths do not interact, so the order does not matter).
  for (std::size_t i = 0; i < n; ++i) {
    const auto slot = static_cast<std::size_t>(columns.slot[i]);
    if (outcome[i] == kRemove)
      Remove(columns.slot[i]);
    else if (outcome[i] == kFused)
      points_[slot].rho = fused_rho[i];
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
