#include "aavio/sim/path_smoothing.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace aavio::sim {

namespace {

constexpr std::size_t kMinPoses = 6;  // two lag-1 pairs of third differences

double Square(double x) { return x * x; }

/// Position (3 columns) and sign-aligned quaternion (4 columns: x, y, z, w) of each pose.
void Columns(const std::vector<geometry::StampedPose>& poses, Eigen::MatrixXd* position,
             Eigen::MatrixXd* quaternion) {
  const Eigen::Index n = static_cast<Eigen::Index>(poses.size());
  position->resize(n, 3);
  quaternion->resize(n, 4);
  Eigen::Vector4d previous = Eigen::Vector4d::Zero();
  for (Eigen::Index i = 0; i < n; ++i) {
    const geometry::RigidTransform& T = poses[static_cast<std::size_t>(i)].T_world_body;
    position->row(i) = T.t.transpose();
    Eigen::Vector4d q = Eigen::Quaterniond(T.R).normalized().coeffs();
    // q and −q are the same rotation; keep the sequence continuous.
    if (i > 0 && q.dot(previous) < 0.0) q = -q;
    quaternion->row(i) = q.transpose();
    previous = q;
  }
}

/// Mean over the columns of σ², from the lag-0 and lag-1 autocovariances of the third
/// differences d = D y: white noise gives E[d_r²] = σ² |D_r|² and E[d_r d_r+1] = σ² D_r·D_r+1
/// (on even stamps 20σ² and −15σ²), while motion smooth at the sampling scale gives nearly equal
/// neighbours, which cancel in the difference.
double NoiseVariance(const Eigen::MatrixXd& y, const Eigen::SparseMatrix<double>& D) {
  const Eigen::MatrixXd d = D * y;
  const Eigen::SparseMatrix<double> gram = D * Eigen::SparseMatrix<double>(D.transpose());
  const Eigen::Index m = d.rows();
  double noise_weight = 0.0;
  for (Eigen::Index r = 0; r + 1 < m; ++r)
    noise_weight += gram.coeff(r, r) - gram.coeff(r, r + 1);
  double sum = 0.0;
  for (Eigen::Index c = 0; c < y.cols(); ++c) {
    const Eigen::VectorXd col = d.col(c);
    const double lag0 = col.head(m - 1).squaredNorm();
    const double lag1 = col.head(m - 1).dot(col.tail(m - 1));
    sum += std::max(0.0, (lag0 - lag1) / noise_weight);
  }
  return sum / static_cast<double>(y.cols());
}

/// Forward differences divided by (t_{i+k} − t_i) / k: applied three times to D1 = Δ/Δt, the
/// rows approximate the third derivative at uneven stamps.
Eigen::SparseMatrix<double> DividedDifference(const std::vector<double>& t_s, int order) {
  const Eigen::Index n = static_cast<Eigen::Index>(t_s.size());
  Eigen::SparseMatrix<double> D(n, n);
  D.setIdentity();
  for (int k = 1; k <= order; ++k) {
    const Eigen::Index rows = n - k;
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index i = 0; i < rows; ++i) {
      const double scale =
          k / (t_s[static_cast<std::size_t>(i + k)] - t_s[static_cast<std::size_t>(i)]);
      entries.emplace_back(i, i, -scale);
      entries.emplace_back(i, i + 1, scale);
    }
    Eigen::SparseMatrix<double> step(rows, rows + 1);
    step.setFromTriplets(entries.begin(), entries.end());
    D = (step * D).pruned();
  }
  return D;
}

/// The Whittaker–Henderson smoother with λ chosen so that the rms residual per column matches
/// √variance; returns the input when the variance is zero.
Eigen::MatrixXd Smooth(const Eigen::MatrixXd& y, const Eigen::SparseMatrix<double>& penalty,
                       double variance) {
  if (variance <= 0.0) return y;
  const Eigen::Index n = y.rows();
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  solver.analyzePattern(identity + penalty);
  const auto solve = [&](double log_lambda, Eigen::MatrixXd* z) {
    solver.factorize(identity + std::pow(10.0, log_lambda) * penalty);
    *z = solver.solve(y);
    return (y - *z).squaredNorm() / static_cast<double>(y.size());
  };
  // The residual grows monotonically with λ: bisect log₁₀ λ.
  double lo = -8.0, hi = 16.0;
  Eigen::MatrixXd z;
  if (solve(hi, &z) <= variance) return z;  // even the stiffest fit stays within the noise
  for (int iteration = 0; iteration < 48; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    (solve(mid, &z) < variance ? lo : hi) = mid;
  }
  solve(lo, &z);
  return z;
}

/// h³ D³ at the poses' stamps, h their median spacing: on even stamps the plain third
/// difference, so λ and the noise weights are free of the time unit.
Eigen::SparseMatrix<double> ThirdDifference(const std::vector<geometry::StampedPose>& poses) {
  std::vector<double> t_s;
  t_s.reserve(poses.size());
  for (const geometry::StampedPose& p : poses)
    t_s.push_back(NsToSeconds(p.t_ns - poses.front().t_ns));
  std::vector<double> spacing(poses.size() - 1);
  for (std::size_t i = 0; i + 1 < t_s.size(); ++i) spacing[i] = t_s[i + 1] - t_s[i];
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  const double h_s = spacing[spacing.size() / 2];
  return h_s * h_s * h_s * DividedDifference(t_s, 3);
}

}  // namespace

PathNoise EstimatePathNoise(const std::vector<geometry::StampedPose>& poses) {
  PathNoise noise;
  if (poses.size() < kMinPoses) return noise;
  Eigen::MatrixXd position, quaternion;
  Columns(poses, &position, &quaternion);
  const Eigen::SparseMatrix<double> D = ThirdDifference(poses);
  noise.position_m = std::sqrt(NoiseVariance(position, D));
  // A small rotation δθ moves the unit quaternion by δθ / 2, spread over its four components:
  // rms angle = 2 √(4 σ²) for a per-component variance σ².
  noise.rotation_rad = 4.0 * std::sqrt(NoiseVariance(quaternion, D));
  return noise;
}

Expected<SmoothedPath> SmoothRecordedPath(const std::vector<geometry::StampedPose>& poses) {
  for (std::size_t i = 1; i < poses.size(); ++i) {
    if (poses[i].t_ns <= poses[i - 1].t_ns) {
      return InvalidArgument("pose stamps must increase strictly (pose " + std::to_string(i) +
                             " is not after pose " + std::to_string(i - 1) + ")");
    }
  }
  SmoothedPath out;
  out.poses = poses;
  if (poses.size() < kMinPoses) return out;
  Eigen::MatrixXd position, quaternion;
  Columns(poses, &position, &quaternion);
  out.noise = EstimatePathNoise(poses);
  const Eigen::SparseMatrix<double> D = ThirdDifference(poses);
  const Eigen::SparseMatrix<double> penalty = D.transpose() * D;
  const Eigen::MatrixXd p = Smooth(position, penalty, Square(out.noise.position_m));
  const Eigen::MatrixXd q = Smooth(quaternion, penalty, Square(out.noise.rotation_rad / 4.0));
  double rotation_sq = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Index r = static_cast<Eigen::Index>(i);
    geometry::RigidTransform& T = out.poses[i].T_world_body;
    T.t = p.row(r).transpose();
    const Eigen::Vector4d coeffs = q.row(r).transpose();
    T.R = Eigen::Quaterniond(coeffs).normalized().toRotationMatrix();
    rotation_sq += geometry::LogSO3(poses[i].T_world_body.R.transpose() * T.R).squaredNorm();
  }
  const double n = static_cast<double>(poses.size());
  out.position_residual_m = std::sqrt((position - p).squaredNorm() / (3.0 * n));
  out.rotation_residual_rad = std::sqrt(rotation_sq / n);
  return out;
}

}  // namespace aavio::sim
