#include "aavio/geometry/rotation.hpp"

#include <gtest/gtest.h>

#include <random>

namespace aavio::geometry {
namespace {

Eigen::Vector3d RandomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

TEST(Rotation, JacobiansMatchFiniteDifferences) {
  std::mt19937 rng(3);
  for (const double scale : {1e-6, 1e-3, 0.3, 1.5, 3.0}) {
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d w = RandomVector(rng, 1.0).normalized() * scale;
      const Eigen::Matrix3d Jr = RightJacobianSO3(w);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d d = 1e-7 * Eigen::Vector3d::Unit(k);
        // Exp(w + δ) = Exp(w)·Exp(Jr δ): the column is Log(Exp(w)ᵀ Exp(w + δ)) / |δ|.
        const Eigen::Vector3d column = LogSO3(ExpSO3(w).transpose() * ExpSO3(w + d)) / 1e-7;
        EXPECT_LT((column - Jr.col(k)).norm(), 1e-6) << "|w| = " << scale;
      }
      EXPECT_LT((InverseRightJacobianSO3(w) * Jr - Eigen::Matrix3d::Identity()).norm(), 1e-9)
          << "|w| = " << scale;
      // The left Jacobian: Exp(w + δ) = Exp(Jl δ)·Exp(w); Jl(w) = Jr(−w).
      const Eigen::Matrix3d Jl = LeftJacobianSO3(w);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d d = 1e-7 * Eigen::Vector3d::Unit(k);
        const Eigen::Vector3d column = LogSO3(ExpSO3(w + d) * ExpSO3(w).transpose()) / 1e-7;
        EXPECT_LT((column - Jl.col(k)).norm(), 1e-6) << "|w| = " << scale;
      }
      EXPECT_EQ(Jl, RightJacobianSO3(-w));
    }
  }
}

TEST(Rotation, ExpLogRoundTripOverTheWholeRange) {
  std::mt19937 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const double angle = std::uniform_real_distribution<double>(0.0, M_PI - 1e-6)(rng);
    Eigen::Vector3d w = RandomVector(rng, 1.0).normalized() * angle;
    if (i == 0) w = Eigen::Vector3d::Zero();
    if (i == 1) w = Eigen::Vector3d(1e-12, -2e-12, 0.0);
    const Eigen::Matrix3d R = ExpSO3(w);
    EXPECT_LT(MeasureRotationError(R).orthogonality, 1e-12);
    EXPECT_LT((LogSO3(R) - w).norm(), 1e-9) << w.transpose();
  }
}

TEST(Rotation, ExpMatchesEigenAngleAxis) {
  const Eigen::Vector3d w(0.3, -1.2, 0.7);
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  EXPECT_LT((ExpSO3(w) - expected).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Rotation, LogNearPiKeepsTheAngle) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -2).normalized();
  const Eigen::Matrix3d R = ExpSO3(axis * (M_PI - 1e-9));
  EXPECT_NEAR(LogSO3(R).norm(), M_PI - 1e-9, 1e-7);
}

TEST(Rotation, HatVee) {
  const Eigen::Vector3d a(1, -2, 3), b(-0.5, 4, 2);
  EXPECT_LT((Hat(a) * b - a.cross(b)).norm(), 1e-15);
  EXPECT_EQ(Vee(Hat(a)), a);
}

TEST(Rotation, CayleyRoundTripsAndMatchesQuaternion) {
  std::mt19937 rng(3);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d c = RandomVector(rng, 2.0);
    const Eigen::Matrix3d R = CayleyToRotation(c);
    EXPECT_LT(MeasureRotationError(R).orthogonality, 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_LT((RotationToCayley(R) - c).norm(), 1e-9 * (1.0 + c.squaredNorm()));
    // c = tan(θ/2) · axis.
    const Eigen::Vector3d w = LogSO3(R);
    EXPECT_NEAR(std::tan(w.norm() / 2.0), c.norm(), 1e-9 * (1.0 + c.squaredNorm()));
  }
}

TEST(Rotation, CayleyDerivativeAtZeroIsTwiceHat) {
  // docs/tracking.md: ∂R/∂c_j at c = 0 equals 2 [e_j]x.
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
    const Eigen::Matrix3d numeric = (CayleyToRotation(h * e) - CayleyToRotation(-h * e)) / (2 * h);
    EXPECT_LT((numeric - 2.0 * Hat(e)).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(Rotation, QuaternionConversions) {
  const Eigen::Matrix3d R = ExpSO3(Eigen::Vector3d(0.1, 0.2, -2.9));
  const Eigen::Quaterniond q = RotationToQuaternion(R);
  EXPECT_GE(q.w(), 0.0);
  EXPECT_LT((QuaternionToRotation(q) - R).cwiseAbs().maxCoeff(), 1e-14);
  // Unnormalised input is normalised.
  Eigen::Quaterniond q2 = q;
  q2.coeffs() *= 3.0;
  EXPECT_LT((QuaternionToRotation(q2) - R).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Rotation, OrthonormalizeFindsTheNearestRotation) {
  const Eigen::Matrix3d R = ExpSO3(Eigen::Vector3d(0.4, -0.3, 0.2));
  Eigen::Matrix3d noisy = R;
  noisy(0, 1) += 1e-4;
  noisy(2, 2) -= 2e-4;
  const Eigen::Matrix3d fixed = Orthonormalize(noisy);
  EXPECT_LT(MeasureRotationError(fixed).orthogonality, 1e-14);
  EXPECT_LT(RotationDistance(fixed, R), 3e-4);
}

TEST(Rotation, ValidateRotationRejectsReflectionsAndNonRotations) {
  EXPECT_TRUE(ValidateRotation(ExpSO3(Eigen::Vector3d(1, 2, 3)), "R").ok());
  Eigen::Matrix3d reflection = Eigen::Matrix3d::Identity();
  reflection(2, 2) = -1.0;
  Status s = ValidateRotation(reflection, "T_b_c rotation");
  EXPECT_NE(s.message().find("T_b_c rotation is a reflection"), std::string::npos);
  Eigen::Matrix3d scaled = 1.01 * Eigen::Matrix3d::Identity();
  s = ValidateRotation(scaled, "R_rect");
  EXPECT_NE(s.message().find("R_rect is not a rotation"), std::string::npos);
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(0, 0) = std::nan("");
  EXPECT_FALSE(ValidateRotation(nan, "R").ok());
}

}  // namespace
}  // namespace aavio::geometry
