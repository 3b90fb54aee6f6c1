#include "aavio/imu/imu_preintegration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "aavio/geometry/random_draws.hpp"
#include "aavio/geometry/rotation.hpp"

namespace aavio::imu {
namespace {

using geometry::ExpSO3;
using geometry::LogSO3;

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

// An IMU turning and moving smoothly: R(t) = Exp(φ(t)), p(t) analytic.
struct Motion {
  static Eigen::Vector3d Phi(double t) {
    return {0.3 * t, -0.5 * t + 0.2 * t * t, 0.4 * std::sin(t)};
  }
  static Eigen::Vector3d PhiDot(double t) { return {0.3, -0.5 + 0.4 * t, 0.4 * std::cos(t)}; }
  static Eigen::Matrix3d R(double t) { return ExpSO3(Phi(t)); }
  static Eigen::Vector3d P(double t) { return {std::sin(2 * t), 0.5 * std::cos(t), 0.3 * t * t}; }
  static Eigen::Vector3d V(double t) { return {2 * std::cos(2 * t), -0.5 * std::sin(t), 0.6 * t}; }
  static Eigen::Vector3d A(double t) { return {-4 * std::sin(2 * t), -0.5 * std::cos(t), 0.6}; }
  static Eigen::Vector3d Gyro(double t) { return geometry::RightJacobianSO3(Phi(t)) * PhiDot(t); }
  static Eigen::Vector3d Accel(double t) { return R(t).transpose() * (A(t) - kGravity); }
};

std::vector<ImuSample> Samples(double rate_hz, double t_end_s, const Eigen::Vector3d& bg,
                               const Eigen::Vector3d& ba, double gyro_sigma = 0.0,
                               double accel_sigma = 0.0, std::uint64_t seed = 1) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<ImuSample> out;
  for (int k = 0; k / rate_hz <= t_end_s; ++k) {
    const double t = k / rate_hz;
    const Eigen::Vector3d gyro = Motion::Gyro(t) + bg + gyro_sigma * geometry::DrawZyx(n, rng);
    const Eigen::Vector3d accel = Motion::Accel(t) + ba + accel_sigma * geometry::DrawZyx(n, rng);
    out.push_back({SecondsToNs(t), gyro, accel});
  }
  return out;
}

struct Truth {
  Eigen::Matrix3d dR;
  Eigen::Vector3d dv, dp;
};
Truth TruthOver(double ti, double tj) {
  const double dt = tj - ti;
  const Eigen::Matrix3d Ri = Motion::R(ti);
  return {Ri.transpose() * Motion::R(tj),
          Ri.transpose() * (Motion::V(tj) - Motion::V(ti) - kGravity * dt),
          Ri.transpose() *
              (Motion::P(tj) - Motion::P(ti) - Motion::V(ti) * dt - 0.5 * kGravity * dt * dt)};
}

const TimeNs kBegin = 12'345'678, kEnd = 512'345'678;  // between samples

TEST(ImuPreintegration, MatchesTheMotionItIntegrates) {
  for (const double rate : {1000.0, 200.0}) {
    const auto samples = Samples(rate, 0.6, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    Expected<Preintegrated> p =
        Preintegrate(samples, kBegin, kEnd, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), {});
    ASSERT_TRUE(p.ok()) << p.status().message();
    const Truth truth = TruthOver(NsToSeconds(kBegin), NsToSeconds(kEnd));
    // Over half a second of a 2 m/s, 4 m/s² motion: errors of the discretisation only.
    const double scale = rate == 1000.0 ? 1.0 : 25.0;  // O(dt²)
    EXPECT_LT(LogSO3(truth.dR.transpose() * p->delta_R).norm(), 1e-7 * scale) << rate;
    EXPECT_LT((truth.dv - p->delta_v).norm(), 2e-6 * scale) << rate;
    EXPECT_LT((truth.dp - p->delta_p).norm(), 1e-6 * scale) << rate;
    EXPECT_DOUBLE_EQ(p->dt_s, 0.5);
  }
}

TEST(ImuPreintegration, BiasJacobiansCorrectWithoutReintegrating) {
  const Eigen::Vector3d bg(0.01, -0.02, 0.015), ba(0.1, -0.05, 0.08);
  const auto samples = Samples(1000.0, 0.6, bg, ba);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const Preintegrated at_zero = *Preintegrate(samples, kBegin, kEnd, zero, zero, {});
  const Preintegrated exact = *Preintegrate(samples, kBegin, kEnd, bg, ba, {});
  // The bias moves the terms by ~1e-2 rad, ~6e-2 m/s, ~1.5e-2 m; first order leaves < 0.5 %.
  const double moved_R = LogSO3(at_zero.delta_R.transpose() * exact.delta_R).norm();
  const double moved_v = (at_zero.delta_v - exact.delta_v).norm();
  const double moved_p = (at_zero.delta_p - exact.delta_p).norm();
  EXPECT_GT(moved_R, 5e-3);
  EXPECT_GT(moved_v, 2e-2);
  EXPECT_GT(moved_p, 5e-3);
  EXPECT_LT(LogSO3(at_zero.DeltaR(bg).transpose() * exact.delta_R).norm(), 0.005 * moved_R);
  EXPECT_LT((at_zero.DeltaV(bg, ba) - exact.delta_v).norm(), 0.005 * moved_v);
  EXPECT_LT((at_zero.DeltaP(bg, ba) - exact.delta_p).norm(), 0.005 * moved_p);
  // And the biased readings integrated at their bias give the motion.
  const Truth truth = TruthOver(NsToSeconds(kBegin), NsToSeconds(kEnd));
  EXPECT_LT((truth.dp - exact.delta_p).norm(), 1e-5);
}

TEST(ImuPreintegration, CovarianceMatchesTheNoise) {
  // 300 noisy integrations (white noise at 1 kHz): the spread of each term's error against the
  // predicted standard deviation.
  const ImuNoise noise{0.01, 0.1};
  const double rate = 1000.0;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const Preintegrated clean =
      *Preintegrate(Samples(rate, 0.6, zero, zero), kBegin, kEnd, zero, zero, noise);
  Eigen::Matrix<double, 9, 9> empirical = Eigen::Matrix<double, 9, 9>::Zero();
  const int trials = 300;
  for (int i = 0; i < trials; ++i) {
    const auto samples = Samples(rate, 0.6, zero, zero, noise.gyro_noise_density * std::sqrt(rate),
                                 noise.accel_noise_density * std::sqrt(rate), 100 + i);
    const Preintegrated p = *Preintegrate(samples, kBegin, kEnd, zero, zero, noise);
    Eigen::Matrix<double, 9, 1> e;
    e << LogSO3(clean.delta_R.transpose() * p.delta_R), p.delta_v - clean.delta_v,
        p.delta_p - clean.delta_p;
    empirical += e * e.transpose() / trials;
  }
  for (int k = 0; k < 9; ++k) {
    const double predicted = clean.covariance(k, k);
    EXPECT_GT(predicted, 0.0);
    EXPECT_NEAR(empirical(k, k) / predicted, 1.0, 0.3) << "component " << k;
  }
}

TEST(ImuPreintegration, RefusesIntervalsTheSamplesDoNotCover) {
  const auto samples = Samples(1000.0, 0.1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  EXPECT_EQ(Preintegrate(samples, 0, SecondsToNs(0.2), zero, zero, {}).status().code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(Preintegrate(samples, SecondsToNs(0.05), 0, zero, zero, {}).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(Preintegrate({}, 0, 0, zero, zero, {}).status().code(), StatusCode::kOutOfRange);
  std::vector<ImuSample> gap = samples;
  gap.erase(gap.begin() + 20, gap.begin() + 80);  // 60 ms without readings
  EXPECT_EQ(Preintegrate(gap, 0, SecondsToNs(0.1), zero, zero, {}).status().code(),
            StatusCode::kOutOfRange);
  EXPECT_TRUE(Preintegrate(gap, 0, SecondsToNs(0.019), zero, zero, {}).ok());
}

}  // namespace
}  // namespace aavio::imu
