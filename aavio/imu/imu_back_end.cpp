#include "aavio/imu/imu_back_end.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/standstill.hpp"

namespace aavio::imu {
namespace {

using geometry::ExpSO3;
using geometry::Hat;
using geometry::LogSO3;

// The tracking's own noise, as measurements of the window (per pose): a few millimetres and a
// tenth of a degree, what the registration reaches on the twins.
constexpr double kPositionSigmaM = 0.005;
constexpr double kRotationSigmaRad = 0.002;
// How far the biases may move from their previous estimate within one window.
constexpr double kGyroBiasPriorSigma = 0.01;  // rad/s
constexpr double kAccelBiasPriorSigma = 0.1;  // m/s²
// Plausibility of an estimate (else the window starts again).
constexpr double kMaxGyroBias = 0.2;      // rad/s
constexpr double kMaxAccelBias = 1.0;     // m/s²
constexpr double kMaxGravityError = 1.0;  // m/s², of the first, unconstrained estimate of |g|
// A pre-integration is integrated again when the biases moved further than this from the ones
// it was integrated with (its first-order correction would be off).
constexpr double kReintegrateGyro = 0.005, kReintegrateAccel = 0.05;
// At rest: moving slower than this by the estimate (an IMU cannot tell a steady motion from
// rest; the estimate carried through a braking keeps a few tenths of a m/s of its error), and the
// readings those of a sensor at rest (standstill.hpp).
constexpr double kRestSpeed = 0.5;
// The window: tracked poses every 50 ms over the last 2 s (on the rpg twins, 1 or 4 s and 25 or
// 100 ms bridged a dark second worse, and tracked no better).
constexpr double kWindowS = 2.0, kFrameIntervalS = 0.05;
constexpr int kMinFrames = 8;
constexpr double kLongTermS = 20.0;  // the biases' and gravity's memory [s]
constexpr int kIterations = 3;       // from the previous frame's solution

// The weight of a pair's residuals: the inverse of the pre-integration's covariance plus the two
// poses'.
Eigen::Matrix<double, 9, 9> Information(const Preintegrated& p) {
  Eigen::Matrix<double, 9, 9> cov = p.covariance;
  cov.block<3, 3>(0, 0) += 2 * kRotationSigmaRad * kRotationSigmaRad * Eigen::Matrix3d::Identity();
  cov.block<3, 3>(6, 6) += 2 * kPositionSigmaM * kPositionSigmaM * Eigen::Matrix3d::Identity();
  cov.block<3, 3>(3, 3) += 1e-8 * Eigen::Matrix3d::Identity();
  return cov.inverse();
}

// A basis of the plane orthogonal to the unit vector u.
Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& u) {
  const Eigen::Vector3d a =
      std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d b1 = u.cross(a).normalized();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = b1;
  B.col(1) = u.cross(b1);
  return B;
}

}  // namespace

ImuBackEnd::ImuBackEnd(const ImuConfig& config, const geometry::RigidTransform& T_imu_cam)
    : config_(config), T_imu_cam_(T_imu_cam), T_cam_imu_(T_imu_cam.Inverse()) {
  noise_.gyro_noise_density = config.gyro_noise_density;
  noise_.accel_noise_density = config.accel_noise_density;
  long_term_.gyro_bias = state_.gyro_bias = Eigen::Vector3d(config.gyro_bias_rad_s.data());
}

void ImuBackEnd::AddSamples(std::span<const ImuSample> samples) {
  for (const ImuSample& s : samples) {
    if (!samples_.empty() && s.t_ns <= samples_.back().t_ns) continue;
    samples_.push_back(s);
  }
  // Keep from a little before the oldest time still needed: the window's first frame, or the
  // last pose (the start of the next prediction).
  TimeNs keep_from = have_last_ ? last_t_ns_ : (samples_.empty() ? 0 : samples_.back().t_ns);
  if (!frames_.empty()) keep_from = std::min(keep_from, frames_.front().t_ns);
  keep_from -= 20 * kNsPerMs;
  if (have_last_) keep_from = std::min(keep_from, last_t_ns_ - SecondsToNs(kRestSpanS));
  const auto first = std::find_if(samples_.begin(), samples_.end(),
                                  [&](const ImuSample& s) { return s.t_ns >= keep_from; });
  // One sample at or before keep_from stays (pre-integration needs a sample before its start).
  if (first - samples_.begin() > 1) samples_.erase(samples_.begin(), first - 1);
}

void ImuBackEnd::Restart() {
  frames_.clear();
  ready_ = false;
  have_last_ = false;
}

void ImuBackEnd::AddPose(TimeNs t_ns, const geometry::RigidTransform& T_world_cam, bool tracked) {
  const geometry::RigidTransform T_world_imu = T_world_cam * T_cam_imu_;
  // The velocity carried to this pose.
  if (have_last_ && ready_ && t_ns > last_t_ns_) {
    Expected<Preintegrated> p =
        Preintegrate(samples_, last_t_ns_, t_ns, state_.gyro_bias, state_.accel_bias, noise_);
    if (p.ok()) {
      last_v_ += state_.gravity_world * p->dt_s + last_R_ * p->delta_v;
      if (!tracked && AtRest(last_t_ns_, t_ns)) last_v_.setZero();  // a standstill
    } else {
      ready_ = false;  // no IMU over the gap: the velocity is unknown
    }
  }
  if (tracked && (frames_.empty() || t_ns - frames_.back().t_ns >= SecondsToNs(kFrameIntervalS))) {
    Frame frame{t_ns, T_world_imu.R, T_world_imu.t, last_v_, {}, {}};
    bool linked = true;
    if (!frames_.empty()) {
      Expected<Preintegrated> p = Preintegrate(samples_, frames_.back().t_ns, t_ns,
                                               state_.gyro_bias, state_.accel_bias, noise_);
      if (p.ok()) {
        frame.from_previous = *p;
        frame.information = Information(*p);
        if (!ready_) {  // a first guess: the mean velocity since the previous frame
          frame.v_world = (frame.p_world_imu - frames_.back().p_world_imu) / p->dt_s;
        }
      } else {
        linked = false;
      }
    }
    if (!linked) {  // the IMU has a gap: the velocity is unknown; a new window starts here
      frames_.clear();
      ready_ = false;
    }
    frames_.push_back(std::move(frame));
    while (frames_.size() > 2 && frames_.back().t_ns - frames_[1].t_ns >= SecondsToNs(kWindowS)) {
      frames_.pop_front();
    }
    Solve();
    if (ready_) last_v_ = frames_.back().v_world;
  }
  last_t_ns_ = t_ns;
  last_R_ = T_world_imu.R;
  last_p_ = T_world_imu.t;
  have_last_ = true;
}

void ImuBackEnd::Solve() {
  if (static_cast<int>(frames_.size()) < kMinFrames) return;
  // Not yet estimated (or restarted): gravity and the velocities from the linear alignment.
  if (!ready_ && !InitialiseGravityAndVelocities()) return;
  // The window's own estimate of everything, near the long-term biases.
  for (int it = 0; it < kIterations; ++it)
    GaussNewtonStep(/*fix_biases_and_gravity=*/false);
  const bool plausible = state_.gyro_bias.norm() < kMaxGyroBias &&
                         state_.accel_bias.norm() < kMaxAccelBias &&
                         frames_.back().v_world.allFinite();
  if (!plausible) {
    long_term_ = LongTerm{};
    long_term_.gyro_bias = state_.gyro_bias = Eigen::Vector3d(config_.gyro_bias_rad_s.data());
    state_.accel_bias.setZero();
    ready_ = false;
    frames_.clear();
    return;
  }
  // Biases and gravity change slowly: a window's estimate (of its 2 s of noisy data) only moves
  // the long-term one, a running mean at first, then exponentially over kLongTermS.
  // Until the window is half full its estimates are too weak to pool: they replace it.
  LongTerm& lt = long_term_;
  const bool half_full = NsToSeconds(frames_.back().t_ns - frames_.front().t_ns) >= 0.5 * kWindowS;
  const double gain = half_full ? std::max(1.0 / ++lt.solves, kFrameIntervalS / kLongTermS) : 1.0;
  if (lt.solves <= 1) lt.gravity_world = state_.gravity_world;
  lt.gyro_bias += gain * (state_.gyro_bias - lt.gyro_bias);
  lt.accel_bias += gain * (state_.accel_bias - lt.accel_bias);
  const Eigen::Vector3d gravity_moved =
      lt.gravity_world + gain * (state_.gravity_world - lt.gravity_world);
  lt.gravity_world = kGravityMS2 * gravity_moved.normalized();
  // The velocities that go with them.
  state_.gyro_bias = lt.gyro_bias;
  state_.accel_bias = lt.accel_bias;
  state_.gravity_world = lt.gravity_world;
  for (int it = 0; it < 2; ++it)
    GaussNewtonStep(/*fix_biases_and_gravity=*/true);
  ready_ = true;
  state_.t_ns = frames_.back().t_ns;
  state_.velocity_world = frames_.back().v_world;
}

bool ImuBackEnd::InitialiseGravityAndVelocities() {
  // Linear least squares in (v_0 … v_{N−1}, g) with the biases at their estimates, from the
  // velocity and position terms of every pair (VINS-Mono's alignment without scale: stereo has it).
  const int n = static_cast<int>(frames_.size());
  const int unknowns = 3 * n + 3;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(unknowns, unknowns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(unknowns);
  const int g = 3 * n;
  for (int j = 1; j < n; ++j) {
    const int i = j - 1;
    const Frame& fi = frames_[i];
    const Frame& fj = frames_[j];
    const Preintegrated& P = fj.from_previous;
    const double dt = P.dt_s;
    // v_j − v_i − g dt = R_i Δv   and   −v_i dt − ½ g dt² = R_i Δp − (p_j − p_i)   (world frame)
    Eigen::Matrix<double, 6, Eigen::Dynamic> A =
        Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 9);
    A.block<3, 3>(0, 0) = -Eigen::Matrix3d::Identity();
    A.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
    A.block<3, 3>(0, 6) = -dt * Eigen::Matrix3d::Identity();
    A.block<3, 3>(3, 0) = -dt * Eigen::Matrix3d::Identity();
    A.block<3, 3>(3, 6) = -0.5 * dt * dt * Eigen::Matrix3d::Identity();
    Eigen::Matrix<double, 6, 1> y;
    y.head<3>() = fi.R_world_imu * P.DeltaV(state_.gyro_bias, state_.accel_bias);
    y.tail<3>() = fi.R_world_imu * P.DeltaP(state_.gyro_bias, state_.accel_bias) -
                  (fj.p_world_imu - fi.p_world_imu);
    // Weights: the velocity terms by the IMU's noise, the position terms by the poses'.
    Eigen::Matrix<double, 6, 1> w;
    const double sv2 = P.covariance.block<3, 3>(3, 3).trace() / 3.0 + 1e-8;
    const double sp2 =
        P.covariance.block<3, 3>(6, 6).trace() / 3.0 + 2 * kPositionSigmaM * kPositionSigmaM;
    w << Eigen::Vector3d::Constant(1.0 / sv2), Eigen::Vector3d::Constant(1.0 / sp2);
    const int cols[3] = {3 * i, 3 * j, g};
    for (int a = 0; a < 3; ++a) {
      for (int c = 0; c < 3; ++c) {
        H.block<3, 3>(cols[a], cols[c]) +=
            A.block<6, 3>(0, 3 * a).transpose() * w.asDiagonal() * A.block<6, 3>(0, 3 * c);
      }
      b.segment<3>(cols[a]) += A.block<6, 3>(0, 3 * a).transpose() * w.asDiagonal() * y;
    }
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
  if (ldlt.info() != Eigen::Success) return false;
  const Eigen::VectorXd x = ldlt.solve(b);
  if (!x.allFinite()) return false;
  const Eigen::Vector3d gravity = x.segment<3>(g);
  if (std::abs(gravity.norm() - kGravityMS2) > kMaxGravityError) return false;
  state_.gravity_world = gravity.normalized() * kGravityMS2;
  for (int k = 0; k < n; ++k)
    frames_[k].v_world = x.segment<3>(3 * k);
  return true;
}

void ImuBackEnd::ReintegrateFarFromBiases() {
  // The window's own estimate stays near the long-term biases: first order covers it.
  for (std::size_t j = 1; j < frames_.size(); ++j) {
    Preintegrated& P = frames_[j].from_previous;
    if ((P.gyro_bias - state_.gyro_bias).norm() > kReintegrateGyro ||
        (P.accel_bias - state_.accel_bias).norm() > kReintegrateAccel) {
      Expected<Preintegrated> again = Preintegrate(samples_, P.t_begin_ns, P.t_end_ns,
                                                   state_.gyro_bias, state_.accel_bias, noise_);
      if (again.ok()) {
        P = *again;
        frames_[j].information = Information(P);
      }
    }
  }
}

ImuBackEnd::InertialFactor ImuBackEnd::Linearize(
    const Frame& fi, const Frame& fj, const Eigen::Matrix<double, 3, 2>& dg_ddelta) const {
  const Preintegrated& P = fj.from_previous;
  const double dt = P.dt_s;
  const Eigen::Matrix3d Rt = fi.R_world_imu.transpose();
  const Eigen::Vector3d dbg = state_.gyro_bias - P.gyro_bias;
  const Eigen::Vector3d& g = state_.gravity_world;
  InertialFactor f;
  const Eigen::Vector3d r_R = LogSO3(P.DeltaR(state_.gyro_bias).transpose() * Rt * fj.R_world_imu);
  f.r.segment<3>(0) = r_R;
  f.r.segment<3>(3) =
      Rt * (fj.v_world - fi.v_world - g * dt) - P.DeltaV(state_.gyro_bias, state_.accel_bias);
  f.r.segment<3>(6) = Rt * (fj.p_world_imu - fi.p_world_imu - fi.v_world * dt - 0.5 * g * dt * dt) -
                      P.DeltaP(state_.gyro_bias, state_.accel_bias);
  // Jacobian blocks over (v_i, v_j, b_g, b_a, δg).
  f.J.setZero();
  f.J.block<3, 3>(0, 6) = -geometry::InverseRightJacobianSO3(r_R) * ExpSO3(r_R).transpose() *
                          geometry::RightJacobianSO3(P.dR_dbg * dbg) * P.dR_dbg;
  f.J.block<3, 3>(3, 0) = -Rt;
  f.J.block<3, 3>(3, 3) = Rt;
  f.J.block<3, 3>(3, 6) = -P.dv_dbg;
  f.J.block<3, 3>(3, 9) = -P.dv_dba;
  f.J.block<3, 2>(3, 12) = -Rt * dt * dg_ddelta;
  f.J.block<3, 3>(6, 0) = -Rt * dt;
  f.J.block<3, 3>(6, 6) = -P.dp_dbg;
  f.J.block<3, 3>(6, 9) = -P.dp_dba;
  f.J.block<3, 2>(6, 12) = -0.5 * Rt * dt * dt * dg_ddelta;
  return f;
}

double ImuBackEnd::GaussNewtonStep(bool fix_biases_and_gravity) {
  const int n = static_cast<int>(frames_.size());
  const int bg = 3 * n, ba = 3 * n + 3, dg = 3 * n + 6, unknowns = 3 * n + 8;
  if (fix_biases_and_gravity) ReintegrateFarFromBiases();
  const double G = kGravityMS2;
  const Eigen::Vector3d u = state_.gravity_world / G;
  const Eigen::Matrix<double, 3, 2> dg_ddelta = -G * Hat(u) * TangentBasis(u);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(unknowns, unknowns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(unknowns);
  double cost = 0.0;
  for (int j = 1; j < n; ++j) {
    const int i = j - 1;
    const InertialFactor f = Linearize(frames_[i], frames_[j], dg_ddelta);
    const Eigen::Matrix<double, 9, 9>& W = frames_[j].information;
    cost += f.r.dot(W * f.r);
    // The factor's 14 columns scattered into the window's unknowns.
    const int cols[5] = {3 * i, 3 * j, bg, ba, dg};
    const int widths[5] = {3, 3, 3, 3, 2};
    const int offsets[5] = {0, 3, 6, 9, 12};
    const Eigen::Matrix<double, 14, 9> JtW = f.J.transpose() * W;
    const Eigen::Matrix<double, 14, 14> JtWJ = JtW * f.J;
    const Eigen::Matrix<double, 14, 1> JtWr = JtW * f.r;
    for (int a = 0; a < 5; ++a) {
      for (int c = 0; c < 5; ++c) {
        H.block(cols[a], cols[c], widths[a], widths[c]) +=
            JtWJ.block(offsets[a], offsets[c], widths[a], widths[c]);
      }
      b.segment(cols[a], widths[a]) += JtWr.segment(offsets[a], widths[a]);
    }
  }
  // Priors on the biases at the long-term estimates; fixed: only the velocities move.
  const Eigen::Vector3d rg = state_.gyro_bias - long_term_.gyro_bias;
  const Eigen::Vector3d ra = state_.accel_bias - long_term_.accel_bias;
  const double wg = 1.0 / (kGyroBiasPriorSigma * kGyroBiasPriorSigma);
  const double wa = 1.0 / (kAccelBiasPriorSigma * kAccelBiasPriorSigma);
  H.block<3, 3>(bg, bg) += wg * Eigen::Matrix3d::Identity();
  H.block<3, 3>(ba, ba) += wa * Eigen::Matrix3d::Identity();
  b.segment<3>(bg) += wg * rg;
  b.segment<3>(ba) += wa * ra;
  cost += wg * rg.squaredNorm() + wa * ra.squaredNorm();
  if (fix_biases_and_gravity) {
    H.block<8, 8>(bg, bg) += 1e12 * Eigen::Matrix<double, 8, 8>::Identity();
  }

  const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
  if (ldlt.info() != Eigen::Success) return cost;
  const Eigen::VectorXd dx = ldlt.solve(-b);
  if (!dx.allFinite()) return cost;
  for (int k = 0; k < n; ++k)
    frames_[k].v_world += dx.segment<3>(3 * k);
  state_.gyro_bias += dx.segment<3>(bg);
  state_.accel_bias += dx.segment<3>(ba);
  state_.gravity_world = G * (ExpSO3(TangentBasis(u) * dx.segment<2>(dg)) * u);
  return cost;
}

Expected<geometry::RigidTransform> ImuBackEnd::Predict(TimeNs t_ns) const {
  if (!ready_ || !have_last_) return FailedPrecondition("the IMU back-end has no estimate yet");
  Expected<Preintegrated> p =
      Preintegrate(samples_, last_t_ns_, t_ns, state_.gyro_bias, state_.accel_bias, noise_);
  if (!p.ok()) return p.status();
  const double dt = p->dt_s;
  geometry::RigidTransform T_world_imu;
  T_world_imu.R = last_R_ * p->delta_R;
  T_world_imu.t =
      last_p_ + last_v_ * dt + 0.5 * state_.gravity_world * dt * dt + last_R_ * p->delta_p;
  return T_world_imu * T_imu_cam_;
}

bool ImuBackEnd::AtRest(TimeNs t_begin_ns, TimeNs t_end_ns) const {
  if (!ready_ || last_v_.norm() > kRestSpeed) return false;
  return RestReading(samples_, t_begin_ns, t_end_ns, state_.gyro_bias, state_.accel_bias)
      .has_value();
}

}  // namespace aavio::imu
