#include "aavio/eval/alignment.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::eval {
namespace {

// A wavy 3-D path with turning orientation, and the same path moved by M (and scaled).
std::vector<PosePair> MovedPairs(const geometry::RigidTransform& M, double scale) {
  std::vector<PosePair> pairs;
  for (int i = 0; i < 150; ++i) {
    const double s = 0.07 * i;
    geometry::RigidTransform gt;
    gt.R = geometry::ExpSO3(Eigen::Vector3d(0.2 * std::sin(s), 0.1 * s, 0.3 * s));
    gt.t = {2.0 * std::cos(s), std::sin(1.3 * s), 0.3 * std::sin(0.5 * s)};
    geometry::RigidTransform est = M * gt;
    est.t *= scale;
    pairs.push_back({i * 10'000'000LL, est, gt});
  }
  return pairs;
}

double MaxError(const std::vector<PosePair>& pairs, const Similarity& S) {
  double worst = 0.0;
  for (const PosePair& p : pairs)
    worst = std::max(worst, (S.Apply(p.T_world_est.t) - p.T_world_gt.t).norm());
  return worst;
}

TEST(Alignment, PosYawRecoversAYawAndTranslationButNotARoll) {
  geometry::RigidTransform yaw;
  yaw.R = Eigen::AngleAxisd(2.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  yaw.t = {3.0, -2.0, 1.0};
  const auto pairs = MovedPairs(yaw, 1.0);
  const Similarity S = Align(pairs, Alignment::kPosYaw);
  EXPECT_LT(MaxError(pairs, S), 1e-9);
  EXPECT_LT((S.R - yaw.R.transpose()).norm(), 1e-9);
  EXPECT_EQ(S.scale, 1.0);
  // se3 finds it too; a roll is beyond posyaw but not beyond se3.
  geometry::RigidTransform roll = yaw;
  roll.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix() * yaw.R;
  const auto rolled = MovedPairs(roll, 1.0);
  EXPECT_GT(MaxError(rolled, Align(rolled, Alignment::kPosYaw)), 0.05);
  EXPECT_LT(MaxError(rolled, Align(rolled, Alignment::kSe3)), 1e-9);
}

TEST(Alignment, Sim3RecoversScaleAndFirstFramesAlignOnlyThem) {
  geometry::RigidTransform M;
  M.R = geometry::ExpSO3(Eigen::Vector3d(0.3, -0.5, 1.1));
  M.t = {2.0, -1.0, 0.5};
  auto pairs = MovedPairs(M, 0.4);
  const Similarity S = Align(pairs, Alignment::kSim3);
  EXPECT_LT(MaxError(pairs, S), 1e-9);
  EXPECT_NEAR(S.scale, 2.5, 1e-9);
  // Corrupt the second half: aligning on the first 50 frames ignores it.
  for (std::size_t i = 75; i < pairs.size(); ++i)
    pairs[i].T_world_est.t += Eigen::Vector3d(0.0, 0.0, 1.0);
  const Similarity first = Align(pairs, Alignment::kSim3, 50);
  EXPECT_NEAR(first.scale, 2.5, 1e-9);
  EXPECT_GT(std::abs(Align(pairs, Alignment::kSim3).scale - 2.5), 1e-3);
  // Too few pairs: identity.
  const std::vector<PosePair> two(pairs.begin(), pairs.begin() + 2);
  EXPECT_EQ(Align(two, Alignment::kSe3).t, Eigen::Vector3d::Zero());
}

TEST(Alignment, NamesParseAndUnknownOnesAreRefusedWithTheChoices) {
  for (Alignment a : {Alignment::kNone, Alignment::kSe3, Alignment::kSim3, Alignment::kPosYaw})
    EXPECT_EQ(*ParseAlignment(AlignmentName(a)), a);
  const auto bad = ParseAlignment("SE3x");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("posyaw"), std::string::npos);
}

}  // namespace
}  // namespace aavio::eval
