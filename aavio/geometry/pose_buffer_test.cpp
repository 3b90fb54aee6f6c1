#include "aavio/geometry/pose_buffer.hpp"

#include <gtest/gtest.h>

namespace aavio::geometry {
namespace {

RigidTransform PoseAt(double s) {
  return {ExpSO3(Eigen::Vector3d(0, 0.5 * s, 0)), Eigen::Vector3d(s, 2 * s, 0)};
}

TEST(PoseBuffer, InterpolatesBetweenStamps) {
  PoseBuffer buffer;
  const TimeNs t0 = 1518196259772284031LL;  // UNIX-epoch stamps keep all their digits
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(buffer.Insert(t0 + i * 10 * kNsPerMs, PoseAt(0.01 * i)).ok());
  }
  Expected<RigidTransform> exact = buffer.Query(t0 + 20 * kNsPerMs);
  ASSERT_TRUE(exact.ok());
  EXPECT_LT((exact->t - PoseAt(0.02).t).norm(), 1e-15);
  Expected<RigidTransform> mid = buffer.Query(t0 + 25 * kNsPerMs);
  ASSERT_TRUE(mid.ok());
  EXPECT_LT((mid->t - PoseAt(0.025).t).norm(), 1e-12);
  EXPECT_LT(RotationDistance(mid->R, PoseAt(0.025).R), 1e-12);
}

TEST(PoseBuffer, RefusesOutOfRangeUnlessExtrapolationAllowed) {
  PoseBuffer buffer;
  ASSERT_TRUE(buffer.Insert(0, PoseAt(0.0)).ok());
  ASSERT_TRUE(buffer.Insert(kNsPerS, PoseAt(1.0)).ok());
  Expected<RigidTransform> late = buffer.Query(kNsPerS + 1);
  EXPECT_EQ(late.status().code(), StatusCode::kOutOfRange);
  EXPECT_NE(late.status().message().find("buffer holds [0.000000000, 1.000000000]"),
            std::string::npos);
  Expected<RigidTransform> extrapolated = buffer.Query(kNsPerS + kNsPerS / 10, kNsPerS / 5);
  ASSERT_TRUE(extrapolated.ok());
  EXPECT_LT((extrapolated->t - PoseAt(1.1).t).norm(), 1e-12);
  EXPECT_FALSE(PoseBuffer().Query(0).ok());
}

TEST(PoseBuffer, RefusesStampsThatDoNotIncrease) {
  PoseBuffer buffer;
  ASSERT_TRUE(buffer.Insert(100, PoseAt(0)).ok());
  EXPECT_FALSE(buffer.Insert(100, PoseAt(0)).ok());
  EXPECT_FALSE(buffer.Insert(50, PoseAt(0)).ok());
  EXPECT_EQ(buffer.size(), 1u);
}

TEST(PoseBuffer, DropsPosesOlderThanTheHistory) {
  PoseBuffer buffer(1 * kNsPerS);
  for (int i = 0; i <= 30; ++i)
    ASSERT_TRUE(buffer.Insert(i * 100 * kNsPerMs, PoseAt(i)).ok());
  EXPECT_EQ(buffer.newest().t_ns, 3 * kNsPerS);
  EXPECT_EQ(buffer.oldest().t_ns, 2 * kNsPerS);
  EXPECT_FALSE(buffer.Query(kNsPerS).ok());
}

}  // namespace
}  // namespace aavio::geometry
