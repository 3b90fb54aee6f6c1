#include "aavio/imu/inertial_check.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "aavio/imu/imu_test_motion.hpp"

namespace aavio::imu {
namespace {

using test_motion::Imu;
using test_motion::kGyroBias;
using test_motion::kImuCam;
using test_motion::Motion;
using test_motion::Tracked;

struct Verdicts {
  int agreeing = 0, disagreeing = 0;
  TimeNs first_disagreement_ns = -1;
};

// Ticks of 10 ms from t0 to t1: the IMU up to each tick, then the tracked pose, moved by
// `drift(t)` (a divergence of the tracking) from t_drift on.
template <typename Drift>
Verdicts Check(const Motion& motion, InertialCheck* check, const std::vector<ImuSample>& imu,
               double t0, double t1, double t_drift, Drift drift) {
  std::mt19937_64 rng(5);
  Verdicts v;
  std::size_t next = 0;
  for (int tick = 0; t0 + tick * 0.01 <= t1 + 1e-9; ++tick) {
    const double t = t0 + tick * 0.01;
    const std::size_t from = next;
    while (next < imu.size() && imu[next].t_ns <= SecondsToNs(t) + kNsPerMs)
      ++next;
    check->AddSamples(std::span(imu).subspan(from, next - from));
    geometry::RigidTransform T = Tracked(motion, t, rng);
    if (t >= t_drift) T.t += drift(t - t_drift);
    const auto m = check->AddTrackedPose(SecondsToNs(t), T, kGyroBias);
    if (!m) continue;
    EXPECT_EQ(m->gravity_world.allFinite(), true);
    if (m->agrees) {
      ++v.agreeing;
    } else {
      if (v.disagreeing++ == 0) v.first_disagreement_ns = m->t_ns;
    }
  }
  return v;
}

const auto kNoDrift = [](double) { return Eigen::Vector3d::Zero(); };

TEST(InertialCheck, TrackingThatFollowsTheCameraAgrees) {
  // Hand-held and driving, with the twins' IMU noise, its biases (the accelerometer's unknown to
  // the check), a turned and offset camera, and 3 mm / 0.09° tracking noise.
  for (const bool driving : {false, true}) {
    const Motion motion{driving};
    const std::vector<ImuSample> imu = Imu(motion, 11.0, 1);
    InertialCheck check(kImuCam);
    const Verdicts v = Check(motion, &check, imu, 0.0, 10.0, 1e9, kNoDrift);
    EXPECT_EQ(v.disagreeing, 0) << (driving ? "driving" : "hand-held");
    EXPECT_GE(v.agreeing, 35);  // one per 0.25 s after the first 0.5 s
  }
}

TEST(InertialCheck, ADivergingTrackDisagreesWithinHalfASecond) {
  const Motion motion;
  const std::vector<ImuSample> imu = Imu(motion, 6.0, 2);
  // Accelerating away at 1 g from t = 3 s (10 cm after 0.14 s, 45 cm after 0.3 s).
  InertialCheck check(kImuCam);
  const Verdicts v = Check(motion, &check, imu, 0.0, 5.0, 3.0,
                           [](double s) { return Eigen::Vector3d(0.5 * 9.81 * s * s, 0.0, 0.0); });
  EXPECT_GE(v.agreeing, 8);  // before the drift
  ASSERT_GE(v.disagreeing, 1);
  EXPECT_GE(v.first_disagreement_ns, SecondsToNs(2.7));
  EXPECT_LE(v.first_disagreement_ns, SecondsToNs(3.5));
}

TEST(InertialCheck, AConstantVelocityErrorIsNotSeenButALargeJumpIs) {
  const Motion motion;
  const std::vector<ImuSample> imu = Imu(motion, 6.0, 3);
  {
    // A velocity of 0.3 m/s too much: the accelerometer cannot tell (nothing accelerates).
    InertialCheck check(kImuCam);
    const Verdicts v = Check(motion, &check, imu, 0.0, 5.0, 2.0,
                             [](double s) { return Eigen::Vector3d(0.0, 0.3 * s, 0.0); });
    EXPECT_EQ(v.disagreeing, 0);
  }
  {
    // A jump of the track: 2 cm (a slip the registration recovers from) stays inside the
    // tolerance; 30 cm across gravity (4.8 m/s² invented across it: |g| moves by 1.1 m/s² only)
    // does not once gravity's direction is known, nor does 40 cm along it.
    for (const double jump_m : {0.02, 0.3, 0.4}) {
      InertialCheck check(kImuCam);
      const Eigen::Vector3d along = test_motion::kGravity.normalized(),
                            across = along.unitOrthogonal();
      const Eigen::Vector3d step = jump_m < 0.35 ? jump_m * across : jump_m * along;
      const Verdicts v = Check(motion, &check, imu, 0.0, 5.0, 2.0, [step](double) { return step; });
      EXPECT_EQ(v.disagreeing >= 1, jump_m > 0.1) << jump_m;
    }
  }
}

TEST(InertialCheck, APoseOffAtOneAnchorOnlyIsNotALoss) {
  // The track off by 15 cm across gravity for 0.12 s around one anchor, then back (a tick the
  // registration got wrong and the next got right): alone, the measurement with that anchor in
  // the middle sees 2 x 2.4 m/s^2, beyond the tolerance; the velocity over two spans does not
  // change.
  const Motion motion;
  const std::vector<ImuSample> imu = Imu(motion, 6.0, 7);
  const Eigen::Vector3d off = 0.15 * test_motion::kGravity.normalized().unitOrthogonal();
  InertialCheck check(kImuCam);
  const Verdicts v = Check(motion, &check, imu, 0.0, 5.0, 2.45, [&](double s) {
    return s > 0.12 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(off);
  });
  EXPECT_EQ(v.disagreeing, 0);
  EXPECT_GE(v.agreeing, 15);
}

TEST(InertialCheck, NoVerdictAcrossAGapOfTheImuOrARestart) {
  const Motion motion;
  std::vector<ImuSample> imu = Imu(motion, 4.0, 4);
  // No IMU between 1 and 2 s.
  std::erase_if(imu, [](const ImuSample& s) {
    return s.t_ns > SecondsToNs(1.0) && s.t_ns < SecondsToNs(2.0);
  });
  InertialCheck check(kImuCam);
  int measurements = 0;
  std::mt19937_64 rng(6);
  std::size_t next = 0;
  for (int tick = 0; tick <= 300; ++tick) {
    const double t = tick * 0.01;
    const std::size_t from = next;
    while (next < imu.size() && imu[next].t_ns <= SecondsToNs(t) + kNsPerMs)
      ++next;
    check.AddSamples(std::span(imu).subspan(from, next - from));
    if (tick == 250) check.Restart();
    const auto m = check.AddTrackedPose(SecondsToNs(t), Tracked(motion, t, rng), kGyroBias);
    if (!m) continue;
    ++measurements;
    EXPECT_TRUE(m->agrees);
    // None whose anchors span the gap or the restart.
    EXPECT_FALSE(m->t_ns > SecondsToNs(0.76) && m->t_ns < SecondsToNs(2.25)) << m->t_ns;
    EXPECT_FALSE(m->t_ns > SecondsToNs(2.26) && m->t_ns < SecondsToNs(2.75)) << m->t_ns;
  }
  EXPECT_GE(measurements, 3);
}

}  // namespace
}  // namespace aavio::imu
