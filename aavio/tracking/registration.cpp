#include "aavio/tracking/registration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "aavio/geometry/rotation.hpp"

namespace aavio::tracking {
namespace {

constexpr double kMaxCayleyStep = 0.02;       // ≈ 2.3° per LM step
constexpr double kMaxTranslationStep = 0.05;  // m per LM step
// LM stops on a relative cost reduction or a relative step below these ([ESVO]).
constexpr double kFunctionTolerance = 1e-3, kStepTolerance = 1e-3;

// Bilinear interpolation weights at (u, v), shared by the images sampled there; the caller
// checks the bounds.
struct BilinearWeights {
  int x0, y0;
  double w00, w10, w01, w11;
};

BilinearWeights WeightsAt(double u, double v) {
  const int x0 = static_cast<int>(u), y0 = static_cast<int>(v);
  const double fx = u - x0, fy = v - y0;
  return {x0, y0, (1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
}

template <typename T>
double Bilinear(const cv::Mat& image, const BilinearWeights& w) {
  const T* a = image.ptr<T>(w.y0) + w.x0;
  const T* b = image.ptr<T>(w.y0 + 1) + w.x0;
  return w.w00 * static_cast<double>(a[0]) + w.w10 * static_cast<double>(a[1]) +
         w.w01 * static_cast<double>(b[0]) + w.w11 * static_cast<double>(b[1]);
}

}  // namespace

geometry::RigidTransform ApplyIncrement(const geometry::RigidTransform& T_ref_cur,
                                        const Eigen::Matrix<double, 6, 1>& theta) {
  const Eigen::Matrix3d Rc = geometry::CayleyToRotation(theta.head<3>());
  return {geometry::Orthonormalize(Rc * T_ref_cur.R),
          Eigen::Vector3d(theta.tail<3>() + Rc * T_ref_cur.t)};
}

Registration::Registration(std::span<const Eigen::Vector3d> points_ref, const Camera& camera,
                           const TrackingConfig& config, std::uint64_t seed)
    : camera_(camera), config_(config) {
  // A random subset of max_points (partial Fisher–Yates, platform-independent draws).
  std::vector<std::size_t> order(points_ref.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937_64 rng(seed);
  const std::size_t n = std::min(order.size(), static_cast<std::size_t>(config.max_points));
  for (std::size_t i = 0; i < n; ++i) {
    std::swap(order[i], order[i + static_cast<std::size_t>(rng() % (order.size() - i))]);
    points_.push_back(points_ref[order[i]]);
  }
}

void Registration::Linearize(const RegistrationImages& images,
                             const geometry::RigidTransform& T_ref_cur,
                             std::span<const int> indices, Eigen::VectorXd* residuals,
                             Eigen::Matrix<double, Eigen::Dynamic, 6>* jacobian, int* valid) const {
  const Eigen::Matrix3d& R = T_ref_cur.R;
  const Eigen::Matrix3d Rt = R.transpose();
  const double f = camera_.f, delta = config_.huber_threshold;
  residuals->resize(static_cast<Eigen::Index>(indices.size()));
  if (jacobian) jacobian->resize(static_cast<Eigen::Index>(indices.size()), 6);
  *valid = 0;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const Eigen::Index row = static_cast<Eigen::Index>(k);
    const Eigen::Vector3d& p = points_[static_cast<std::size_t>(indices[k])];
    const Eigen::Vector3d q = Rt * (p - T_ref_cur.t);
    double r = 255.0;
    Eigen::Matrix<double, 1, 6> J = Eigen::Matrix<double, 1, 6>::Zero();
    if (q.z() > 1e-6) {
      const double u = f * q.x() / q.z() + camera_.cx, v = f * q.y() / q.z() + camera_.cy;
      const bool inside =
          u >= 0.0 && v >= 0.0 && u < camera_.width - 1.0 && v < camera_.height - 1.0;
      if (inside && images.valid_mask.at<std::uint8_t>(static_cast<int>(v + 0.5),
                                                       static_cast<int>(u + 0.5)) > 125) {
        const BilinearWeights at = WeightsAt(u, v);
        r = Bilinear<std::uint8_t>(images.negative_ts, at);
        if (jacobian) {
          const double gu = Bilinear<float>(images.grad_u, at),
                       gv = Bilinear<float>(images.grad_v, at);
          // ∂r/∂q = ∇I · ∂π/∂q; with a = R (∂r/∂q)ᵀ: ∂r/∂c = 2 (∂r/∂q) Rᵀ [p]× = 2 (a × p)ᵀ and
          // ∂r/∂t = −aᵀ.
          const double inv_z = 1.0 / q.z();
          const Eigen::Vector3d g(f * inv_z * gu, f * inv_z * gv,
                                  -f * inv_z * inv_z * (gu * q.x() + gv * q.y()));
          const Eigen::Vector3d a = R * g;
          J.head<3>() = 2.0 * a.cross(p).transpose();
          J.tail<3>() = -a.transpose();
        }
        ++*valid;
      }
    }
    // Huber: w = 1 below δ, δ/r above; the solver sees √w r (and √w J).
    const double w = r <= delta ? 1.0 : delta / r;
    (*residuals)(row) = std::sqrt(w) * r;
    if (jacobian) jacobian->row(row) = std::sqrt(w) * J;
  }
}

double Registration::Alignment(const RegistrationImages& images,
                               const geometry::RigidTransform& T_ref_cur) const {
  const double delta = config_.huber_threshold;
  auto huber = [delta](double r) { return r <= delta ? r * r : delta * r; };
  const Eigen::Matrix3d Rt = T_ref_cur.R.transpose();
  double points_sum = 0.0;
  int points = 0;
  for (const Eigen::Vector3d& p : points_) {
    const Eigen::Vector3d q = Rt * (p - T_ref_cur.t);
    if (q.z() <= 1e-6) continue;
    const double u = camera_.f * q.x() / q.z() + camera_.cx,
                 v = camera_.f * q.y() / q.z() + camera_.cy;
    if (u < 0.0 || v < 0.0 || u >= camera_.width - 1.0 || v >= camera_.height - 1.0 ||
        images.valid_mask.at<std::uint8_t>(static_cast<int>(v + 0.5), static_cast<int>(u + 0.5)) <=
            125)
      continue;
    points_sum += huber(Bilinear<std::uint8_t>(images.negative_ts, WeightsAt(u, v)));
    ++points;
  }
  // The image: every 4th pixel of every 4th row inside the mask.
  double image_sum = 0.0;
  int pixels = 0;
  for (int y = 0; y < images.negative_ts.rows; y += 4) {
    const std::uint8_t* ts = images.negative_ts.ptr<std::uint8_t>(y);
    const std::uint8_t* mask = images.valid_mask.ptr<std::uint8_t>(y);
    for (int x = 0; x < images.negative_ts.cols; x += 4) {
      if (mask[x] <= 125) continue;
      image_sum += huber(ts[x]);
      ++pixels;
    }
  }
  if (points == 0 || pixels == 0 || image_sum <= 0.0) return 1.0;
  return (points_sum / points) / (image_sum / pixels);
}

RegistrationResult Registration::Solve(
    const RegistrationImages& images, const geometry::RigidTransform& T_ref_cur_init,
    const std::optional<Eigen::Matrix3d>& R_ref_cur_prior) const {
  RegistrationResult result;
  result.T_ref_cur = T_ref_cur_init;
  const int n = static_cast<int>(points_.size());
  const int batch = std::min(config_.batch_size, n);
  if (batch <= 0) return result;
  const int batches = std::max(1, n / batch);
  std::vector<int> indices(static_cast<std::size_t>(batch));
  Eigen::VectorXd r, r_trial;
  Eigen::Matrix<double, Eigen::Dynamic, 6> J;
  int valid = 0;
  // Divergence tests compare costs on the same points: all of them, before and after.
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  auto mean_cost = [&](const geometry::RigidTransform& T, double* valid_fraction) {
    int all_valid = 0;
    Linearize(images, T, all, &r_trial, nullptr, &all_valid);
    if (valid_fraction) *valid_fraction = static_cast<double>(all_valid) / n;
    return r_trial.squaredNorm() / n;
  };
  result.initial_cost = mean_cost(result.T_ref_cur, &result.valid_fraction);
  // The gyroscope prior as a cost term: w‖K δ‖², δ = log(R R_priorᵀ), K = 180/π. The increment
  // R ← R(c) R moves δ by ≈ 2c, so with the unnormalised JᵀJ (data cost × count) its rows are
  // √(w·count)·K·2I with residual √(w·count)·K·δ.
  const bool use_prior = R_ref_cur_prior.has_value() && config_.gyro_rotation_weight > 0.0;
  constexpr double kDegPerRad = 180.0 / M_PI;
  auto deviation = [&](const Eigen::Matrix3d& R) {
    return geometry::LogSO3(R * R_ref_cur_prior->transpose());
  };
  const double kt = config_.translation_prior_weight * 1e4;  // per cm² → per m²
  const Eigen::Vector3d t_prior = T_ref_cur_init.t;
  auto prior_cost = [&](const geometry::RigidTransform& T) {
    return (use_prior ? config_.gyro_rotation_weight * kDegPerRad * kDegPerRad *
                            deviation(T.R).squaredNorm()
                      : 0.0) +
           kt * (T.t - t_prior).squaredNorm();
  };
  double lambda = 1e-4;
  // One LM step on the points `idx` (damping adapted across steps, as the reference): true if a
  // step was accepted; `small` when its cost reduction was below the tolerance.
  auto lm_step = [&](const std::vector<int>& idx, bool* small, Eigen::Matrix<double, 6, 1>* step) {
    const double count = static_cast<double>(idx.size());
    Linearize(images, result.T_ref_cur, idx, &r, &J, &valid);
    const double cost = r.squaredNorm() / count + prior_cost(result.T_ref_cur);
    Eigen::Matrix<double, 6, 6> H = J.transpose() * J;
    Eigen::Matrix<double, 6, 1> g = J.transpose() * r;
    if (use_prior) {
      const double k = config_.gyro_rotation_weight * count * kDegPerRad * kDegPerRad;
      H.topLeftCorner<3, 3>() += 4.0 * k * Eigen::Matrix3d::Identity();
      g.head<3>() += 2.0 * k * deviation(result.T_ref_cur.R);
    }
    if (kt > 0.0) {
      H.bottomRightCorner<3, 3>() += kt * count * Eigen::Matrix3d::Identity();
      g.tail<3>() += kt * count * (result.T_ref_cur.t - t_prior);
    }
    for (int attempt = 0; attempt < 6; ++attempt) {
      Eigen::Matrix<double, 6, 6> A = H;
      A.diagonal() += lambda * H.diagonal() + Eigen::Matrix<double, 6, 1>::Constant(1e-9);
      Eigen::Matrix<double, 6, 1> theta = A.ldlt().solve(-g);
      // A step larger than a tick's plausible motion comes from a degenerate batch (few edges,
      // flat surface): shorten it rather than jump (Cayley c ≈ θ/2).
      const double scale = std::max({1.0, theta.head<3>().norm() / kMaxCayleyStep,
                                     theta.tail<3>().norm() / kMaxTranslationStep});
      theta /= scale;
      const geometry::RigidTransform trial = ApplyIncrement(result.T_ref_cur, theta);
      int trial_valid = 0;
      Linearize(images, trial, idx, &r_trial, nullptr, &trial_valid);
      const double trial_cost = r_trial.squaredNorm() / count + prior_cost(trial);
      if (trial_cost < cost) {
        result.T_ref_cur = trial;
        lambda = std::max(1e-7, lambda * 0.1);
        *small = (cost - trial_cost) / cost < kFunctionTolerance;
        *step = theta;
        return true;
      }
      lambda *= 10.0;
    }
    return false;
  };
  // Mini-batches (the reference): consecutive batches of the shuffled points.
  bool small_reduction = false;
  Eigen::Matrix<double, 6, 1> theta = Eigen::Matrix<double, 6, 1>::Zero();
  for (int iteration = 0; iteration < config_.max_iterations && !small_reduction; ++iteration) {
    const int b = iteration % batches;
    std::iota(indices.begin(), indices.end(), b * batch);
    const bool accepted = lm_step(indices, &small_reduction, &theta);
    result.iterations = iteration + 1;
    if (!accepted) {
      if (batches == 1) break;  // no progress possible on the only batch
    } else if (theta.norm() < kStepTolerance * 1e-2) {
      break;
    }
  }
  // Polish (aavio): a few steps on all points, so that the last batch's sampling noise does not
  // stay in the pose.
  if (batches > 1) {
    bool small = false;
    for (int k = 0; k < config_.polish_iterations && !small; ++k) {
      ++result.iterations;
      if (!lm_step(all, &small, &theta)) break;
    }
  }
  result.final_cost = mean_cost(result.T_ref_cur, nullptr);
  result.alignment = Alignment(images, result.T_ref_cur);
  return result;
}

}  // namespace aavio::tracking
