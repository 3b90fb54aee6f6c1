#include "aavio/sim/motions.hpp"

#include <cmath>
#include <random>

namespace aavio::sim {

namespace {

constexpr double kRate = 200.0;  // poses per second handed to the spline

/// A smooth random signal: a sum of sinusoids with random phases in a frequency band.
struct Wave {
  double amp[3], freq[3], phase[3];
  Wave(std::mt19937_64& rng, double amplitude, double f_lo, double f_hi) {
    std::uniform_real_distribution<double> f(f_lo, f_hi), p(0, 2 * M_PI), a(0.5, 1.0);
    for (int k = 0; k < 3; ++k) {
      amp[k] = amplitude * a(rng) / 1.6;
      freq[k] = f(rng);
      phase[k] = p(rng);
    }
  }
  double operator()(double t) const {
    double v = 0.0;
    for (int k = 0; k < 3; ++k)
      v += amp[k] * (std::sin(2 * M_PI * freq[k] * t + phase[k]) - std::sin(phase[k]));
    return v;  // 0 at t = 0
  }
};

}  // namespace

std::vector<geometry::StampedPose> HandHeldMotion(double duration_s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Wave tx(rng, 0.3, 0.15, 0.6), ty(rng, 0.15, 0.15, 0.6), tz(rng, 0.3, 0.1, 0.4);
  const Wave rx(rng, 0.25, 0.2, 0.8), ry(rng, 0.35, 0.15, 0.7), rz(rng, 0.15, 0.2, 0.8);
  std::vector<geometry::StampedPose> poses;
  for (double t = 0.0; t <= duration_s + 1e-9; t += 1.0 / kRate) {
    poses.push_back({SecondsToNs(t),
                     {geometry::ExpSO3(Eigen::Vector3d(rx(t), ry(t), rz(t))),
                      Eigen::Vector3d(tx(t), ty(t), tz(t) + 0.05 * t)}});
  }
  return poses;
}

std::vector<geometry::StampedPose> SinusoidMotion(double duration_s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> period(3.0, 6.0), phase(0.0, 2.0 * M_PI),
      angle(5.0 * M_PI / 180.0, 8.0 * M_PI / 180.0);
  const double amplitude[6] = {0.25, 0.1, 0.2, angle(rng), angle(rng), angle(rng)};
  double omega[6], phi[6];
  for (int k = 0; k < 6; ++k) {
    omega[k] = 2.0 * M_PI / period(rng);
    phi[k] = phase(rng);
  }
  auto axis = [&](int k, double t) {
    return amplitude[k] * (std::sin(omega[k] * t + phi[k]) - std::sin(phi[k]));
  };
  std::vector<geometry::StampedPose> poses;
  for (double t = 0.0; t <= duration_s + 1e-9; t += 1.0 / kRate) {
    poses.push_back({SecondsToNs(t),
                     {geometry::ExpSO3(Eigen::Vector3d(axis(3, t), axis(4, t), axis(5, t))),
                      Eigen::Vector3d(axis(0, t), axis(1, t), axis(2, t))}});
  }
  return poses;
}

std::vector<geometry::StampedPose> DrivingMotion(double duration_s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Speed profile: cruise changes every few seconds between 5 and 12 m/s, one stop in the middle.
  const double stop_at = duration_s * (0.4 + 0.2 * unit(rng));
  std::vector<double> cruise;
  for (int k = 0; k < static_cast<int>(duration_s / 4.0) + 2; ++k)
    cruise.push_back(5.0 + 7.0 * unit(rng));
  // Turns: yaw rate bumps of ±0.25 rad/s lasting ~4 s.
  std::vector<std::pair<double, double>> turns;  // (centre time, peak yaw rate)
  for (double t = 3.0; t < duration_s; t += 6.0 + 6.0 * unit(rng)) {
    const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
    turns.emplace_back(t, sign * (0.15 + 0.15 * unit(rng)));
  }
  const Wave pitch(rng, 0.01, 0.5, 2.0), roll(rng, 0.01, 0.5, 2.0), bounce(rng, 0.02, 1.0, 3.0);
  auto speed_at = [&](double t) {
    const double k = t / 4.0;
    const std::size_t i = static_cast<std::size_t>(k);
    const double s = k - static_cast<double>(i);
    const double smooth = s * s * (3.0 - 2.0 * s);
    double v = cruise[i] + (cruise[i + 1] - cruise[i]) * smooth;
    // Smoothly down to 0 around the stop (2 s standing, 3 s to brake and to pull away).
    const double d = std::abs(t - stop_at);
    if (d < 1.0) return 0.0;
    if (d < 4.0) v *= 0.5 - 0.5 * std::cos(M_PI * (d - 1.0) / 3.0);
    return v;
  };
  auto yaw_rate_at = [&](double t) {
    double w = 0.0;
    for (const auto& [centre, peak] : turns)
      w += peak * std::exp(-0.5 * std::pow((t - centre) / 1.2, 2));
    return w * std::min(1.0, speed_at(t) / 5.0);  // no turning on the spot
  };
  std::vector<geometry::StampedPose> poses;
  double yaw = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  const double dt = 1.0 / kRate;
  for (double t = 0.0; t <= duration_s + 1e-9; t += dt) {
    // Camera frame: z forward, y down; yaw turns about −y (the world's up).
    const Eigen::Matrix3d R = geometry::ExpSO3(Eigen::Vector3d(0, -yaw, 0)) *
                              geometry::ExpSO3(Eigen::Vector3d(pitch(t), 0, roll(t)));
    poses.push_back({SecondsToNs(t), {R, p + Eigen::Vector3d(0, bounce(t), 0)}});
    const Eigen::Vector3d forward(std::sin(yaw), 0.0, std::cos(yaw));
    p += forward * speed_at(t) * dt;
    yaw -= yaw_rate_at(t) * dt;
  }
  return poses;
}

std::vector<geometry::StampedPose> DroneMotion(double duration_s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Wave tx(rng, 1.5, 0.05, 0.25), ty(rng, 0.4, 0.05, 0.2), tz(rng, 1.5, 0.05, 0.25);
  const Wave yaw(rng, 0.6, 0.05, 0.2), tilt_x(rng, 0.08, 0.2, 0.6), tilt_z(rng, 0.08, 0.2, 0.6);
  std::vector<geometry::StampedPose> poses;
  for (double t = 0.0; t <= duration_s + 1e-9; t += 1.0 / kRate) {
    const Eigen::Matrix3d R = geometry::ExpSO3(Eigen::Vector3d(0, yaw(t), 0)) *
                              geometry::ExpSO3(Eigen::Vector3d(tilt_x(t), 0, tilt_z(t)));
    poses.push_back({SecondsToNs(t), {R, Eigen::Vector3d(tx(t), ty(t), tz(t))}});
  }
  return poses;
}

}  // namespace aavio::sim
