#include "aavio/tracking/registration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "aavio/geometry/random_draws.hpp"
#include "aavio/geometry/rotation.hpp"
#include "aavio/tracking/synthetic_scene.hpp"

namespace aavio::tracking {
namespace {

using testing::EdgeMap;
using testing::Images;
using testing::kCamera;
using testing::Render;

TEST(Registration, AnalyticJacobianMatchesFiniteDifferences) {
  // A smooth image so that finite differences are meaningful.
  cv::Mat smooth(kCamera.height, kCamera.width, CV_32FC1);
  for (int v = 0; v < kCamera.height; ++v)
    for (int u = 0; u < kCamera.width; ++u)
      smooth.at<float>(v, u) =
          static_cast<float>(120 + 60 * std::sin(u * 0.07) * std::cos(v * 0.05));
  Images images;
  smooth.convertTo(images.negative, CV_8U);
  // Gradients of the smooth function itself (the uint8 image rounds; use the float one).
  cv::Sobel(smooth, images.du, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(smooth, images.dv, CV_32F, 0, 1, 3, 1.0 / 8.0);
  images.valid = cv::Mat(kCamera.height, kCamera.width, CV_8UC1, cv::Scalar(255));
  smooth.convertTo(images.negative, CV_8U);
  TrackingConfig config;
  config.huber_threshold = 1e9;  // plain least squares for the comparison
  const std::vector<Eigen::Vector3d> map = EdgeMap(3);
  const Registration reg(map, kCamera, config, 1);
  geometry::RigidTransform T;
  T.R = geometry::ExpSO3(Eigen::Vector3d(0.02, -0.03, 0.01));
  T.t = {0.05, -0.02, 0.1};
  std::vector<int> idx(50);
  std::iota(idx.begin(), idx.end(), 0);
  Eigen::VectorXd r0;
  Eigen::Matrix<double, Eigen::Dynamic, 6> J;
  int valid = 0;
  reg.Linearize({images.negative, images.du, images.dv, images.valid}, T, idx, &r0, &J, &valid);
  ASSERT_GT(valid, 40);
  // Finite differences on the float image: replace the uint8 residual by the float function.
  auto value = [&](const geometry::RigidTransform& pose, int i) {
    const Eigen::Vector3d q = pose.Inverse() * reg.points()[static_cast<std::size_t>(i)];
    const double u = kCamera.f * q.x() / q.z() + kCamera.cx,
                 v = kCamera.f * q.y() / q.z() + kCamera.cy;
    return 120 + 60 * std::sin(u * 0.07) * std::cos(v * 0.05);
  };
  int compared = 0;
  for (int i = 0; i < 50; ++i) {
    if (J.row(i).isZero()) continue;
    for (int j = 0; j < 6; ++j) {
      Eigen::Matrix<double, 6, 1> h = Eigen::Matrix<double, 6, 1>::Zero();
      h(j) = 1e-6;
      const double numeric =
          (value(ApplyIncrement(T, h), i) - value(ApplyIncrement(T, -h), i)) / 2e-6;
      // Sobel/8 of a smooth function is its derivative to within a few percent.
      EXPECT_NEAR(J(i, j), numeric, 0.03 * std::abs(numeric) + 0.5) << "point " << i << " θ" << j;
    }
    ++compared;
  }
  EXPECT_GT(compared, 40);
}

// The edge map seen from a pose a little off the reference, rendered: a registration problem
// with a known answer.
struct PosedEdgeScene {
  std::vector<Eigen::Vector3d> map = EdgeMap(5);
  geometry::RigidTransform truth = [] {
    geometry::RigidTransform T;
    T.R = geometry::ExpSO3(Eigen::Vector3d(0.01, 0.02, -0.01));
    T.t = {0.03, 0.01, 0.05};
    return T;
  }();
  Images images = Render(map, truth);
  RegistrationImages Input() const { return {images.negative, images.du, images.dv, images.valid}; }
};

TEST(Registration, ConvergesFromTwoDegreesAndFiveCentimetres) {
  const PosedEdgeScene scene;
  const std::vector<Eigen::Vector3d>& map = scene.map;
  const geometry::RigidTransform& truth = scene.truth;
  const RegistrationImages input = scene.Input();
  // Mini-batches of 300 (the reference) need 20 iterations (ESVO2 rpg; 158 of 200 with 10, 192
  // with 10 + 3 on all points); the presets' 20 + 3 on all points. (Every step on all points
  // stalls half the time: the batches' randomness is what gets out of shallow minima.)
  for (const auto& [batch_size, iterations, polish] :
       {std::tuple{300, 20, 0}, std::tuple{300, 20, 3}}) {
    TrackingConfig config;
    config.batch_size = batch_size;
    config.max_iterations = iterations;
    config.polish_iterations = polish;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int converged = 0;
    const int trials = 200;
    double worst_angle = 0.0;
    for (int trial = 0; trial < trials; ++trial) {
      // A perturbation of 2° about a random axis and 5 cm in a random direction.
      const Eigen::Vector3d axis = geometry::DrawZyx(unit, rng), dir = geometry::DrawZyx(unit, rng);
      geometry::RigidTransform start = truth;
      start.R = geometry::ExpSO3(axis.normalized() * (2.0 * M_PI / 180.0)) * truth.R;
      start.t = truth.t + 0.05 * dir.normalized();
      const Registration reg(map, kCamera, config, static_cast<std::uint64_t>(trial));
      const RegistrationResult result = reg.Solve(input, start);
      const double angle =
          geometry::LogSO3(result.T_ref_cur.R * truth.R.transpose()).norm() * 180 / M_PI;
      const double offset = (result.T_ref_cur.t - truth.t).norm();
      worst_angle = std::max(worst_angle, angle);
      if (angle < 0.2 && offset < 0.01) ++converged;
    }
    EXPECT_GE(converged, trials * 99 / 100)
        << "batch " << batch_size << ", worst angle " << worst_angle << "°";
    std::printf(
        "registration from ±2° / ±5 cm, batches of %d, %d iterations + %d on all: %d of "
        "%d trials within 0.2° and 1 cm\n",
        batch_size, iterations, polish, converged, trials);
  }
}

// Why the LM stopped: the steps ran out; the cost stopped falling near the optimum; no map.
TEST(Registration, SaysWhyItStopped) {
  const PosedEdgeScene scene;
  const RegistrationImages input = scene.Input();
  geometry::RigidTransform far = scene.truth;
  far.R = geometry::ExpSO3(Eigen::Vector3d(0.0, 2.0 * M_PI / 180.0, 0.0)) * far.R;
  far.t += Eigen::Vector3d(0.05, 0.0, 0.0);
  TrackingConfig config;
  config.max_iterations = 2;
  config.polish_iterations = 3;
  const RegistrationResult cut = Registration(scene.map, kCamera, config, 1).Solve(input, far);
  EXPECT_EQ(cut.stop, RegistrationStop::kMaxIterations);
  EXPECT_GE(cut.iterations, 3);  // 2 on batches and at least one polishing step
  EXPECT_LE(cut.iterations, 5);
  config.max_iterations = 20;
  geometry::RigidTransform near = scene.truth;
  near.t += Eigen::Vector3d(0.002, 0.0, 0.0);
  const RegistrationResult done = Registration(scene.map, kCamera, config, 1).Solve(input, near);
  EXPECT_TRUE(done.stop == RegistrationStop::kConverged ||
              done.stop == RegistrationStop::kSmallStep)
      << RegistrationStopName(done.stop);
  EXPECT_LT(done.iterations, 20);
  const RegistrationResult none = Registration({}, kCamera, config, 1).Solve(input, near);
  EXPECT_EQ(none.stop, RegistrationStop::kNoPoints);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_STREQ(RegistrationStopName(RegistrationStop::kNoDescent), "no_descent");
}

// Alignment: at the true pose the map sits on the dark edges, far below the image's mean cost;
// on a time surface of the same darkness at random places (noise), no better than anywhere.
TEST(Registration, AlignmentSaysWhetherTheMapFitsBetterThanAnywhere) {
  const PosedEdgeScene scene;
  TrackingConfig config;
  const Registration reg(scene.map, kCamera, config, 1);
  const RegistrationResult aligned = reg.Solve(scene.Input(), scene.truth);
  EXPECT_LT(aligned.alignment, 0.3);
  // The same image with its pixels shuffled: the same histogram, no structure.
  cv::Mat flat = scene.images.negative.reshape(1, 1).clone();
  std::mt19937 rng(5);
  std::shuffle(flat.begin<std::uint8_t>(), flat.end<std::uint8_t>(), rng);
  Images noise = scene.images;
  noise.negative = flat.reshape(1, kCamera.height);
  const RegistrationResult lost =
      reg.Solve({noise.negative, noise.du, noise.dv, noise.valid}, scene.truth);
  EXPECT_GT(lost.alignment, 0.9);
  EXPECT_LT(lost.alignment, 1.1);
}

// The gyroscope's rotation as a soft prior: weight 0 leaves the data alone, a heavy weight holds
// the rotation at the prior (and a wrong sign of its gradient would leave LM stuck at the start).
TEST(Registration, RotationPriorPullsTowardsTheGyroscope) {
  const PosedEdgeScene scene;
  const std::vector<Eigen::Vector3d>& map = scene.map;
  const geometry::RigidTransform& truth = scene.truth;
  const RegistrationImages input = scene.Input();
  geometry::RigidTransform start = truth;
  start.R = geometry::ExpSO3(Eigen::Vector3d(0.0, 1.0, 0.0) * (1.0 * M_PI / 180.0)) * truth.R;
  const Eigen::Matrix3d prior =
      geometry::ExpSO3(Eigen::Vector3d(1.0, 0.0, 0.0) * (0.5 * M_PI / 180.0)) * truth.R;
  auto degrees_from = [](const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    return geometry::LogSO3(a * b.transpose()).norm() * 180.0 / M_PI;
  };
  TrackingConfig config;
  config.max_iterations = 20;
  config.polish_iterations = 3;
  for (const double weight : {0.0, 1e6}) {
    config.gyro_rotation_weight = weight;
    const Registration reg(map, kCamera, config, 3);
    const RegistrationResult result = reg.Solve(input, start, prior);
    if (weight == 0.0) {
      EXPECT_LT(degrees_from(result.T_ref_cur.R, truth.R), 0.1);
    } else {
      EXPECT_LT(degrees_from(result.T_ref_cur.R, prior), 0.05);
    }
  }
}

// The predicted translation as a soft prior: weight 0 leaves the data alone, heavier weights
// hold the translation closer and closer to the prediction (a wrong sign of the prior's gradient
// would push it away or leave LM stuck), a very heavy one at it.
TEST(Registration, TranslationPriorHoldsThePrediction) {
  const PosedEdgeScene scene;
  const RegistrationImages input = scene.Input();
  geometry::RigidTransform start = scene.truth;
  start.t += Eigen::Vector3d(0.02, -0.01, 0.0);
  TrackingConfig config;
  config.max_iterations = 20;
  config.polish_iterations = 3;
  double previous_from_start = 1.0;
  for (const double weight : {0.0, 1.0, 10.0, 1e6}) {
    config.translation_prior_weight = weight;
    const Registration reg(scene.map, kCamera, config, 3);
    const RegistrationResult result = reg.Solve(input, start);
    const double from_truth = (result.T_ref_cur.t - scene.truth.t).norm();
    const double from_start = (result.T_ref_cur.t - start.t).norm();
    if (weight == 0.0) {
      EXPECT_LT(from_truth, 0.003);
    }
    EXPECT_LT(from_start, previous_from_start - 0.002) << "weight " << weight;
    previous_from_start = from_start;
  }
  EXPECT_LT(previous_from_start, 0.001);
}

}  // namespace
}  // namespace aavio::tracking
