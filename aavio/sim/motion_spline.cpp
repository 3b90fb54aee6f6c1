#include "aavio/sim/motion_spline.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::sim {

namespace {

using geometry::ExpSO3;
using geometry::LogSO3;

/// Cumulative basis of the uniform cubic B-spline and its derivative in u (Kim et al. 1995):
/// R(u) = C₀ · Exp(λ₁ d₁) · Exp(λ₂ d₂) · Exp(λ₃ d₃), d_j = Log(C_{j−1}ᵀ C_j).
void CumulativeBasis(double u, double lambda[3], double dlambda[3]) {
  const double u2 = u * u, u3 = u2 * u;
  lambda[0] = (5.0 + 3.0 * u - 3.0 * u2 + u3) / 6.0;
  lambda[1] = (1.0 + 3.0 * u + 3.0 * u2 - 2.0 * u3) / 6.0;
  lambda[2] = u3 / 6.0;
  dlambda[0] = (3.0 - 6.0 * u + 3.0 * u2) / 6.0;
  dlambda[1] = (3.0 + 6.0 * u - 6.0 * u2) / 6.0;
  dlambda[2] = 3.0 * u2 / 6.0;
}

}  // namespace

Expected<MotionSpline> MotionSpline::Fit(const std::vector<geometry::StampedPose>& poses,
                                         TimeNs knot_interval_ns) {
  if (poses.size() < 2) return InvalidArgument("a motion spline needs at least 2 poses");
  for (std::size_t i = 1; i < poses.size(); ++i) {
    if (poses[i].t_ns <= poses[i - 1].t_ns) {
      return InvalidArgument("pose stamps must increase strictly (pose " + std::to_string(i) + ")");
    }
  }
  MotionSpline s;
  s.t_begin_ns_ = poses.front().t_ns;
  s.t_end_ns_ = poses.back().t_ns;
  const std::size_t n = poses.size();
  s.times_s_.reserve(n);
  for (const geometry::StampedPose& p : poses)
    s.times_s_.push_back(NsToSeconds(p.t_ns - s.t_begin_ns_));

  // Natural cubic spline per axis (second derivative 0 at both ends): tridiagonal solve for the
  // second derivatives M_i, then per-interval coefficients.
  std::vector<Eigen::Vector3d> M(n, Eigen::Vector3d::Zero());
  if (n > 2) {
    std::vector<double> diag(n, 0.0), upper(n, 0.0);
    std::vector<Eigen::Vector3d> rhs(n, Eigen::Vector3d::Zero());
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double h0 = s.times_s_[i] - s.times_s_[i - 1];
      const double h1 = s.times_s_[i + 1] - s.times_s_[i];
      diag[i] = 2.0 * (h0 + h1);
      upper[i] = h1;
      rhs[i] = 6.0 * ((poses[i + 1].T_world_body.t - poses[i].T_world_body.t) / h1 -
                      (poses[i].T_world_body.t - poses[i - 1].T_world_body.t) / h0);
    }
    // Thomas algorithm on rows 1..n−2 (lower coefficient of row i is h_{i−1}).
    for (std::size_t i = 2; i + 1 < n; ++i) {
      const double lower = s.times_s_[i] - s.times_s_[i - 1];
      const double m = lower / diag[i - 1];
      diag[i] -= m * upper[i - 1];
      rhs[i] -= m * rhs[i - 1];
    }
    for (std::size_t i = n - 2; i >= 1; --i) {
      M[i] = (rhs[i] - upper[i] * M[i + 1]) / diag[i];
      if (i == 1) break;
    }
  }
  s.segments_.resize(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double h = s.times_s_[i + 1] - s.times_s_[i];
    const Eigen::Vector3d& p0 = poses[i].T_world_body.t;
    const Eigen::Vector3d& p1 = poses[i + 1].T_world_body.t;
    CubicSegment& seg = s.segments_[i];
    seg.a = p0;
    seg.b = (p1 - p0) / h - h * (2.0 * M[i] + M[i + 1]) / 6.0;
    seg.c = M[i] / 2.0;
    seg.d = (M[i + 1] - M[i]) / (6.0 * h);
  }

  // Rotation: uniform knots covering [0, T]; targets by slerp of the poses at the knot times.
  const double duration_s = s.times_s_.back();
  double dt = NsToSeconds(knot_interval_ns);
  if (knot_interval_ns <= 0) {
    std::vector<double> gaps;
    for (std::size_t i = 1; i < n; ++i)
      gaps.push_back(s.times_s_[i] - s.times_s_[i - 1]);
    std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2),
                     gaps.end());
    dt = std::clamp(gaps[gaps.size() / 2], 0.005, 0.1);
  }
  const std::size_t knots = static_cast<std::size_t>(std::ceil(duration_s / dt)) + 1;
  s.knot_dt_s_ = duration_s / static_cast<double>(knots - 1);
  geometry::PoseBuffer buffer(0);
  for (const geometry::StampedPose& p : poses)
    (void)buffer.Insert(p.t_ns, p.T_world_body);
  std::vector<Eigen::Matrix3d> target(knots);
  for (std::size_t k = 0; k < knots; ++k) {
    const TimeNs t = s.t_begin_ns_ + SecondsToNs(static_cast<double>(k) * s.knot_dt_s_);
    target[k] = buffer.Query(std::min(t, s.t_end_ns_))->R;
  }
  // Control points C_0 .. C_{K+1}: knot k sits at the start of segment k, whose controls are
  // C_k .. C_{k+3}; start from the targets and correct by the residual (fixed point).
  s.control_.resize(knots + 2);
  for (std::size_t j = 0; j < s.control_.size(); ++j) {
    s.control_[j] = target[std::min(knots - 1, j == 0 ? 0 : j - 1)];
  }
  for (int iteration = 0; iteration < 50; ++iteration) {
    double worst = 0.0;
    for (std::size_t k = 0; k < knots; ++k) {
      const Eigen::Matrix3d R = s.RotationAt(static_cast<double>(k) * s.knot_dt_s_, nullptr);
      const Eigen::Vector3d error = LogSO3(R.transpose() * target[k]);
      worst = std::max(worst, error.norm());
      s.control_[k + 1] = geometry::Orthonormalize(s.control_[k + 1] * ExpSO3(error));
    }
    s.control_.front() = s.control_[1] * (s.control_[1].transpose() * s.control_[2]).transpose();
    s.control_.back() = s.control_[knots] * (s.control_[knots - 1].transpose() * s.control_[knots]);
    if (worst < 1e-10) break;
  }
  for (const geometry::StampedPose& p : poses) {
    s.max_fit_error_rad_ = std::max(
        s.max_fit_error_rad_, geometry::RotationDistance(s.Rotation(p.t_ns), p.T_world_body.R));
  }
  return s;
}

std::size_t MotionSpline::Segment(double t_s) const {
  const auto it = std::upper_bound(times_s_.begin(), times_s_.end(), t_s);
  const std::size_t i =
      it == times_s_.begin() ? 0 : static_cast<std::size_t>(it - times_s_.begin()) - 1;
  return std::min(i, segments_.size() - 1);
}

void MotionSpline::Knot(double t_s, std::size_t* i, double* u) const {
  const double x = std::clamp(t_s / knot_dt_s_, 0.0, static_cast<double>(control_.size() - 3));
  *i = std::min(static_cast<std::size_t>(x), control_.size() - 4);
  *u = x - static_cast<double>(*i);
}

Eigen::Matrix3d MotionSpline::RotationAt(double t_s, Eigen::Vector3d* omega_body) const {
  std::size_t i;
  double u;
  Knot(t_s, &i, &u);
  double lambda[3], dlambda[3];
  CumulativeBasis(u, lambda, dlambda);
  Eigen::Matrix3d A[3];
  Eigen::Vector3d d[3];
  Eigen::Matrix3d R = control_[i];
  for (int j = 0; j < 3; ++j) {
    d[j] = LogSO3(control_[i + j].transpose() * control_[i + j + 1]);
    A[j] = ExpSO3(lambda[j] * d[j]);
    R = R * A[j];
  }
  if (omega_body) {
    // Rᵀ Ṙ = Σ_j (A_{j+1} … A₃)ᵀ [λ̇_j d_j]x (A_{j+1} … A₃): ω = A₃ᵀA₂ᵀ λ̇₁d₁ + A₃ᵀ λ̇₂d₂ + λ̇₃d₃.
    const double rate = 1.0 / knot_dt_s_;
    *omega_body =
        rate * (A[2].transpose() * (A[1].transpose() * (dlambda[0] * d[0]) + dlambda[1] * d[1]) +
                dlambda[2] * d[2]);
  }
  return R;
}

geometry::RigidTransform MotionSpline::Pose(TimeNs t_ns) const {
  return {Rotation(t_ns), Position(t_ns)};
}

Eigen::Vector3d MotionSpline::Position(TimeNs t_ns) const {
  const double t = std::clamp(NsToSeconds(t_ns - t_begin_ns_), 0.0, times_s_.back());
  const std::size_t i = Segment(t);
  const double s = t - times_s_[i];
  const CubicSegment& c = segments_[i];
  return c.a + s * (c.b + s * (c.c + s * c.d));
}

Eigen::Vector3d MotionSpline::LinearVelocity(TimeNs t_ns) const {
  const double t = std::clamp(NsToSeconds(t_ns - t_begin_ns_), 0.0, times_s_.back());
  const std::size_t i = Segment(t);
  const double s = t - times_s_[i];
  const CubicSegment& c = segments_[i];
  return c.b + s * (2.0 * c.c + 3.0 * s * c.d);
}

Eigen::Vector3d MotionSpline::LinearAcceleration(TimeNs t_ns) const {
  const double t = std::clamp(NsToSeconds(t_ns - t_begin_ns_), 0.0, times_s_.back());
  const std::size_t i = Segment(t);
  const double s = t - times_s_[i];
  const CubicSegment& c = segments_[i];
  return 2.0 * c.c + 6.0 * s * c.d;
}

Eigen::Matrix3d MotionSpline::Rotation(TimeNs t_ns) const {
  return RotationAt(NsToSeconds(t_ns - t_begin_ns_), nullptr);
}

Eigen::Vector3d MotionSpline::AngularVelocity(TimeNs t_ns) const {
  Eigen::Vector3d omega;
  RotationAt(NsToSeconds(t_ns - t_begin_ns_), &omega);
  return omega;
}

}  // namespace aavio::sim
