#include "aavio/tracking/registration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>

#include "aavio/geometry/rotation.hpp"

namespace aavio::tracking {
namespace {

// LM stops on a relative cost reduction or a relative step below these ([ESVO]).
constexpr double kFunctionTolerance = 1e-3, kStepTolerance = 1e-3;
constexpr double kDegPerRad = 180.0 / M_PI;

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

// A map point in the current camera and where it lands; `inside`: in front, and its bilinear
// neighbourhood inside the image (the mask is tested when it is sampled).
struct Projected {
  Eigen::Vector3d q;
  double u = 0.0, v = 0.0;
  bool inside = false;
};

Projected Project(const Eigen::Vector3d& p_ref, const Eigen::Matrix3d& R_cur_ref,
                  const Eigen::Vector3d& t_ref_cur, const Camera& camera) {
  Projected at;
  at.q = R_cur_ref * (p_ref - t_ref_cur);
  if (!(at.q.z() > 1e-6)) return at;
  at.u = camera.f * at.q.x() / at.q.z() + camera.cx;
  at.v = camera.f * at.q.y() / at.q.z() + camera.cy;
  at.inside = at.u >= 0.0 && at.v >= 0.0 && at.u < camera.width - 1.0 && at.v < camera.height - 1.0;
  return at;
}

// Asks for the two image rows a projected point's samples will read (the points come in random
// order, so each one's pixels would otherwise be a cache miss when they are read).
void Prefetch(const RegistrationImages& images, const Projected& at, bool gradients) {
  if (!at.inside) return;
  const int x = static_cast<int>(at.u), y = static_cast<int>(at.v);
  for (const int row : {y, y + 1}) {
    __builtin_prefetch(images.valid_mask.ptr<std::uint8_t>(row) + x);
    __builtin_prefetch(images.negative_ts.ptr<std::uint8_t>(row) + x);
    if (gradients) {
      __builtin_prefetch(images.grad_u.ptr<float>(row) + x);
      __builtin_prefetch(images.grad_v.ptr<float>(row) + x);
    }
  }
}

// The soft priors of the cost: the gyroscope's rotation, w‖K δ‖² with δ = log(R R_priorᵀ) and
// K = 180/π (deg²), and the predicted translation, kt‖t − t_prior‖² (kt per m²).
struct Priors {
  std::optional<Eigen::Matrix3d> R_prior;  // only when weighted
  double rotation_weight = 0.0;
  Eigen::Vector3d t_prior = Eigen::Vector3d::Zero();
  double kt = 0.0;

  Eigen::Vector3d Deviation(const Eigen::Matrix3d& R) const {
    return geometry::LogSO3(R * R_prior->transpose());
  }
  double Cost(const geometry::RigidTransform& T) const {
    return (R_prior ? rotation_weight * kDegPerRad * kDegPerRad * Deviation(T.R).squaredNorm()
                    : 0.0) +
           kt * (T.t - t_prior).squaredNorm();
  }
};

// The registration's cost on a set of map points (a mini-batch, or all): the mean robust
// squared residual, plus the priors.
class PointsCost final : public PoseCost {
 public:
  PointsCost(const Registration& registration, const RegistrationImages& images,
             const Priors& priors)
      : registration_(registration), images_(images), priors_(priors) {}
  void SetPoints(std::span<const int> indices) { indices_ = indices; }

  Linearization Linearize(const geometry::RigidTransform& T) const override {
    const double count = static_cast<double>(indices_.size());
    int valid = 0;
    registration_.Linearize(images_, T, indices_, &r_, &J_, &valid);
    Linearization at;
    at.cost = r_.squaredNorm() / count + priors_.Cost(T);
    at.H = J_.transpose() * J_;
    at.g = J_.transpose() * r_;
    // The rotation prior's rows: the increment R ← R(c) R moves δ by ≈ 2c, so with the
    // unnormalised JᵀJ (data cost × count) they are √(w·count)·K·2I with residual
    // √(w·count)·K·δ.
    if (priors_.R_prior) {
      const double k = priors_.rotation_weight * count * kDegPerRad * kDegPerRad;
      at.H.topLeftCorner<3, 3>() += 4.0 * k * Eigen::Matrix3d::Identity();
      at.g.head<3>() += 2.0 * k * priors_.Deviation(T.R);
    }
    if (priors_.kt > 0.0) {
      at.H.bottomRightCorner<3, 3>() += priors_.kt * count * Eigen::Matrix3d::Identity();
      at.g.tail<3>() += priors_.kt * count * (T.t - priors_.t_prior);
    }
    return at;
  }
  double Cost(const geometry::RigidTransform& T) const override {
    int valid = 0;
    registration_.Linearize(images_, T, indices_, &r_trial_, nullptr, &valid);
    return r_trial_.squaredNorm() / static_cast<double>(indices_.size()) + priors_.Cost(T);
  }

 private:
  const Registration& registration_;
  const RegistrationImages& images_;
  const Priors& priors_;
  std::span<const int> indices_;
  mutable Eigen::VectorXd r_, r_trial_;
  mutable Eigen::Matrix<double, Eigen::Dynamic, 6> J_;
};

}  // namespace

const char* RegistrationStopName(RegistrationStop stop) {
  switch (stop) {
    case RegistrationStop::kMaxIterations:
      return "max_iterations";
    case RegistrationStop::kConverged:
      return "converged";
    case RegistrationStop::kSmallStep:
      return "small_step";
    case RegistrationStop::kNoDescent:
      return "no_descent";
    case RegistrationStop::kNoPoints:
      return "no_points";
  }
  return "?";
}

Registration::Registration(std::span<const Eigen::Vector3d> points_ref, const Camera& camera,
                           const TrackingConfig& config, std::uint64_t seed,
                           const std::function<bool(const Eigen::Vector3d& p_ref)>& keep)
    : camera_(camera), config_(config) {
  // A random subset of max_points (partial Fisher–Yates, platform-independent draws).
  std::vector<std::size_t> order(points_ref.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937_64 rng(seed);
  const std::size_t n = static_cast<std::size_t>(config.max_points);
  for (std::size_t i = 0; i < order.size() && points_.size() < n; ++i) {
    std::swap(order[i], order[i + static_cast<std::size_t>(rng() % (order.size() - i))]);
    const Eigen::Vector3d& p = points_ref[order[i]];
    if (keep && !keep(p)) {
      ++left_out_;
      continue;
    }
    points_.push_back(p);
  }
}

void Registration::Linearize(const RegistrationImages& images,
                             const geometry::RigidTransform& T_ref_cur,
                             std::span<const int> indices, Eigen::VectorXd* residuals,
                             Eigen::Matrix<double, Eigen::Dynamic, 6>* jacobian, int* valid) const {
  Linearize(images, T_ref_cur, indices, residuals, jacobian, valid, nullptr);
}

void Registration::Linearize(const RegistrationImages& images,
                             const geometry::RigidTransform& T_ref_cur,
                             std::span<const int> indices, Eigen::VectorXd* residuals,
                             Eigen::Matrix<double, Eigen::Dynamic, 6>* jacobian, int* valid,
                             double* inside_robust_sum) const {
  const Eigen::Matrix3d& R = T_ref_cur.R;
  const Eigen::Matrix3d Rt = R.transpose();
  const double f = camera_.f, delta = config_.huber_threshold;
  residuals->resize(static_cast<Eigen::Index>(indices.size()));
  if (jacobian) jacobian->resize(static_cast<Eigen::Index>(indices.size()), 6);
  *valid = 0;
  // In chunks: every point of a chunk projected (its rows prefetched), then sampled in order.
  constexpr std::size_t kChunk = 32;
  std::array<Projected, kChunk> chunk;
  for (std::size_t begin = 0; begin < indices.size(); begin += kChunk) {
    const std::size_t end = std::min(indices.size(), begin + kChunk);
    for (std::size_t k = begin; k < end; ++k) {
      chunk[k - begin] =
          Project(points_[static_cast<std::size_t>(indices[k])], Rt, T_ref_cur.t, camera_);
      Prefetch(images, chunk[k - begin], jacobian != nullptr);
    }
    for (std::size_t k = begin; k < end; ++k) {
      const Projected& at = chunk[k - begin];
      const Eigen::Vector3d& p = points_[static_cast<std::size_t>(indices[k])];
      const Eigen::Vector3d& q = at.q;
      double r = 255.0;
      Eigen::Matrix<double, 1, 6> J = Eigen::Matrix<double, 1, 6>::Zero();
      if (at.inside && images.valid_mask.at<std::uint8_t>(static_cast<int>(at.v + 0.5),
                                                          static_cast<int>(at.u + 0.5)) > 125) {
        const BilinearWeights w = WeightsAt(at.u, at.v);
        r = Bilinear<std::uint8_t>(images.negative_ts, w);
        if (inside_robust_sum) *inside_robust_sum += r <= delta ? r * r : delta * r;
        if (jacobian) {
          const double gu = Bilinear<float>(images.grad_u, w),
                       gv = Bilinear<float>(images.grad_v, w);
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
      // Huber: w = 1 below δ, δ/r above; the solver sees √w r (and √w J).
      const double w = r <= delta ? 1.0 : delta / r;
      (*residuals)(static_cast<Eigen::Index>(k)) = std::sqrt(w) * r;
      if (jacobian) jacobian->row(static_cast<Eigen::Index>(k)) = std::sqrt(w) * J;
    }
  }
}

double Registration::Alignment(const RegistrationImages& images, double points_sum,
                               int points) const {
  const double delta = config_.huber_threshold;
  auto huber = [delta](double r) { return r <= delta ? r * r : delta * r; };
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
  if (batch <= 0) return result;  // RegistrationStop::kNoPoints
  const int batches = std::max(1, n / batch);
  // Divergence tests compare costs on the same points: all of them, before and after.
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  result.initial_cost = MeanCost(images, result.T_ref_cur, all, &result.valid_fraction);
  Priors priors;
  if (R_ref_cur_prior && config_.gyro_rotation_weight > 0.0) {
    priors.R_prior = R_ref_cur_prior;
    priors.rotation_weight = config_.gyro_rotation_weight;
  }
  priors.t_prior = T_ref_cur_init.t;
  priors.kt = config_.translation_prior_weight * 1e4;  // per cm² → per m²
  PointsCost cost(*this, images, priors);
  PoseLevenbergMarquardt lm({.function_tolerance = kFunctionTolerance});
  // Mini-batches (the reference): consecutive batches of the shuffled points.
  std::vector<int> indices(static_cast<std::size_t>(batch));
  result.stop = RegistrationStop::kMaxIterations;
  for (int iteration = 0; iteration < config_.max_iterations; ++iteration) {
    std::iota(indices.begin(), indices.end(), (iteration % batches) * batch);
    cost.SetPoints(indices);
    const LmStep step = lm.Step(cost, &result.T_ref_cur);
    result.iterations = iteration + 1;
    if (step.accepted && step.small_reduction) {
      result.stop = RegistrationStop::kConverged;
      break;
    }
    if (!step.accepted && batches == 1) {
      result.stop = RegistrationStop::kNoDescent;  // no progress possible on the only batch
      break;
    }
    if (step.accepted && step.theta.norm() < kStepTolerance * 1e-2) {
      result.stop = RegistrationStop::kSmallStep;
      break;
    }
  }
  // Polish (aavio): a few steps on all points, so that the last batch's sampling noise does not
  // stay in the pose.
  if (batches > 1) {
    cost.SetPoints(all);
    for (int k = 0; k < config_.polish_iterations; ++k) {
      ++result.iterations;
      const LmStep step = lm.Step(cost, &result.T_ref_cur);
      if (!step.accepted || step.small_reduction) break;
    }
  }
  // The final cost and the alignment's points from one pass over all points.
  Eigen::VectorXd r;
  int inside = 0;
  double inside_sum = 0.0;
  Linearize(images, result.T_ref_cur, all, &r, nullptr, &inside, &inside_sum);
  result.final_cost = r.squaredNorm() / static_cast<double>(n);
  result.alignment = Alignment(images, inside_sum, inside);
  return result;
}

double Registration::MeanCost(const RegistrationImages& images,
                              const geometry::RigidTransform& T_ref_cur,
                              std::span<const int> indices, double* valid_fraction) const {
  Eigen::VectorXd r;
  int valid = 0;
  Linearize(images, T_ref_cur, indices, &r, nullptr, &valid);
  const double n = static_cast<double>(indices.size());
  if (valid_fraction) *valid_fraction = valid / n;
  return r.squaredNorm() / n;
}

}  // namespace aavio::tracking
