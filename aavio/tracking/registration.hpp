#pragma once
/// Time-surface registration (docs/tracking.md): the pose of the current camera relative to
/// the map's reference frame that puts the map points on the dark ridges of the current negative
/// time surface,
///   min_θ Σ_i Huber( N(π(T_cur,ref(θ) p_i)) ),  N = negative TS (bilinear),
/// parametrised by a Cayley + translation increment on T_ref,cur (left composition in the
/// reference frame), solved by Levenberg–Marquardt (pose_lm.hpp) over mini-batches of a random
/// subset of the map, one LM step per batch, then a few on all points, with the analytic
/// Jacobian ∇N · ∂π/∂q · ∂q/∂θ,
///   ∂q/∂δ = −Rᵀ, ∂q/∂c = 2 Rᵀ [p]×  (at θ = 0, (R, t) = T_ref,cur, p in the reference frame).

#include <Eigen/Core>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/tracking/pose_lm.hpp"
#include "aavio/tracking/tracking_config.hpp"

namespace aavio::tracking {

/// The rectified left camera: focal length and principal point [px], size.
struct Camera {
  int width = 0, height = 0;
  double f = 0.0, cx = 0.0, cy = 0.0;
};

struct RegistrationImages {
  const cv::Mat& negative_ts;  ///< CV_8UC1
  const cv::Mat& grad_u;       ///< CV_32FC1, Sobel/8 of negative_ts
  const cv::Mat& grad_v;
  const cv::Mat& valid_mask;  ///< CV_8UC1, > 125 = usable
};

/// Why the LM stopped stepping through the mini-batches (before its polish on all points).
enum class RegistrationStop {
  kMaxIterations,  ///< tracking.max_iterations steps ran
  kConverged,      ///< a step lowered the cost by less than 0.1 % of it
  kSmallStep,      ///< a step moved the pose by less than 1e-5 (Cayley + metres)
  kNoDescent,      ///< no damping lowered the cost, and there is only one batch
  kNoPoints,       ///< no map point to register
};
/// "max_iterations", "converged", "small_step", "no_descent" or "no_points" (summary.json).
const char* RegistrationStopName(RegistrationStop stop);

struct RegistrationResult {
  geometry::RigidTransform T_ref_cur;
  int iterations = 0;
  RegistrationStop stop = RegistrationStop::kNoPoints;
  double initial_cost = 0.0, final_cost = 0.0;  ///< mean robust cost per point
  double valid_fraction = 0.0;  ///< share of points landing inside the image and mask
  /// At the final pose: the mean cost of the points that land inside, over the mean cost of the
  /// image's usable pixels — how much better the map fits here than anywhere (1: no better).
  double alignment = 1.0;
};

class Registration {
 public:
  /// `points_ref`: the map in its reference frame. A random subset of max_points is drawn from
  /// `seed` (same seed, same subset). With `keep`, a drawn point it rejects is left out and the
  /// draw goes on until max_points are kept or the map is exhausted (left_out() counts them).
  Registration(std::span<const Eigen::Vector3d> points_ref, const Camera& camera,
               const TrackingConfig& config, std::uint64_t seed,
               const std::function<bool(const Eigen::Vector3d& p_ref)>& keep = {});

  /// LM from T_ref_cur_init. With `R_ref_cur_prior` and config.gyro_rotation_weight > 0 the cost
  /// also holds weight·‖log(R R_priorᵀ)‖² [deg²] (the gyroscope's rotation as a soft prior); with
  /// config.translation_prior_weight > 0, weight·‖t − t_init‖² [cm²] (the predicted translation).
  RegistrationResult Solve(const RegistrationImages& images,
                           const geometry::RigidTransform& T_ref_cur_init,
                           const std::optional<Eigen::Matrix3d>& R_ref_cur_prior = {}) const;

  /// Residuals (robustly weighted: √w r) and their Jacobian rows for `indices` at T_ref_cur;
  /// out-of-image points give r = 255 (weighted) and a zero row. Exposed for tests.
  void Linearize(const RegistrationImages& images, const geometry::RigidTransform& T_ref_cur,
                 std::span<const int> indices, Eigen::VectorXd* residuals,
                 Eigen::Matrix<double, Eigen::Dynamic, 6>* jacobian, int* valid) const;

  std::size_t size() const { return points_.size(); }
  int left_out() const { return left_out_; }  ///< drawn points `keep` rejected
  const std::vector<Eigen::Vector3d>& points() const { return points_; }  ///< the chosen subset

 private:
  /// Linearize, also adding up the robust cost ρ(r) of the points inside the image and mask
  /// (`inside_robust_sum`, if given).
  void Linearize(const RegistrationImages& images, const geometry::RigidTransform& T_ref_cur,
                 std::span<const int> indices, Eigen::VectorXd* residuals,
                 Eigen::Matrix<double, Eigen::Dynamic, 6>* jacobian, int* valid,
                 double* inside_robust_sum) const;
  /// The mean robust cost of the `points` map points inside the image (their sum `points_sum`)
  /// over that of the image's pixels: well below 1 when the map sits on the edges.
  double Alignment(const RegistrationImages& images, double points_sum, int points) const;
  // The mean robust squared residual of the points `indices` at T_ref_cur, and the share of
  // them inside the image and mask.
  double MeanCost(const RegistrationImages& images, const geometry::RigidTransform& T_ref_cur,
                  std::span<const int> indices, double* valid_fraction) const;
  std::vector<Eigen::Vector3d> points_;  // the chosen subset, reference frame
  Camera camera_;
  TrackingConfig config_;
  int left_out_ = 0;
};

}  // namespace aavio::tracking
