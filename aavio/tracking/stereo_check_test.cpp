#include "aavio/tracking/stereo_check.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "aavio/tracking/registration.hpp"
#include "aavio/tracking/synthetic_scene.hpp"
#include "aavio/tracking/tracker.hpp"

namespace aavio::tracking {
namespace {

// A 240×180 rectified pair, f = 200 px, baseline 10 cm: disparity 20 / z.
const Camera kPair{240, 180, 200.0, 120.0, 90.0};
constexpr double kFb = 20.0;
const StereoCheckRig kRig{kFb, 0.0, 0, 60, 0.1};
constexpr int kWallDisparity = 10;               // a wall at 2 m
constexpr int kPersonDisparity = 25;             // someone at 0.8 m, in front of part of it
constexpr int kPersonLo = 100, kPersonHi = 190;  // the person's left-image columns

// A left time surface of random blotches (no two stretches of a row alike), and the right one
// the scene gives: the wall at kWallDisparity, the person's columns at kPersonDisparity.
struct Pair {
  cv::Mat left, right, valid;
};
Pair MakePair(bool with_person) {
  Pair pair;
  cv::Mat noise(kPair.height, kPair.width + 80, CV_32FC1);
  cv::RNG rng(7);  // its own generator: the same pair whichever tests run before
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(noise, noise, cv::Size(3, 3), 0.0);
  noise.convertTo(noise, CV_8U);
  pair.left = noise(cv::Rect(0, 0, kPair.width, kPair.height)).clone();
  pair.right = cv::Mat(kPair.height, kPair.width, CV_8UC1);
  for (int v = 0; v < kPair.height; ++v) {
    for (int u_r = 0; u_r < kPair.width; ++u_r) {
      // The left pixel this right pixel sees: the person where it covers the left view.
      int u_l = u_r + kWallDisparity;
      if (with_person && u_r + kPersonDisparity >= kPersonLo && u_r + kPersonDisparity <= kPersonHi)
        u_l = u_r + kPersonDisparity;
      pair.right.at<std::uint8_t>(v, u_r) = noise.at<std::uint8_t>(v, u_l);
    }
  }
  pair.valid = cv::Mat(kPair.height, kPair.width, CV_8UC1, cv::Scalar(255));
  return pair;
}

// The wall point seen at left pixel (u, v).
Eigen::Vector3d WallPoint(double u, double v) {
  const double z = kFb / kWallDisparity;
  return {(u - kPair.cx) * z / kPair.f, (v - kPair.cy) * z / kPair.f, z};
}

TEST(StereoCheck, KeepsAPointThePairStillShows) {
  const Pair pair = MakePair(false);
  const StereoCheck check(pair.left, pair.right, pair.valid, kPair, kRig);
  for (int u : {40, 120, 170, 215})
    EXPECT_FALSE(check.SeesSomethingElse(WallPoint(u, 60))) << u;
}

TEST(StereoCheck, LeavesOutAPointSomethingNearerHides) {
  const Pair pair = MakePair(true);
  const StereoCheck check(pair.left, pair.right, pair.valid, kPair, kRig);
  // Behind the person: the left camera sees the person there, who matches at 25 px, not 10.
  for (int u : {130, 145, 160})
    EXPECT_TRUE(check.SeesSomethingElse(WallPoint(u, 60))) << u;
  // Beside the person the wall still matches at its own disparity.
  for (int u : {40, 70, 215})
    EXPECT_FALSE(check.SeesSomethingElse(WallPoint(u, 60))) << u;
  // The person's own depth there is fine.
  const double z = kFb / kPersonDisparity;
  EXPECT_FALSE(check.SeesSomethingElse({(145 - kPair.cx) * z / kPair.f, 0.0, z}));
}

TEST(StereoCheck, KeepsWhatItCannotTell) {
  Pair pair = MakePair(true);
  // No events around the point (an empty patch): nothing to tell.
  pair.left(cv::Rect(130, 40, 40, 40)).setTo(0);
  // A right view that matches nothing (another camera's noise): no evidence of another depth.
  cv::Mat other(kPair.height, kPair.width, CV_8UC1);
  cv::RNG rng(11);
  rng.fill(other, cv::RNG::UNIFORM, 0, 255);
  const StereoCheck empty(pair.left, pair.right, pair.valid, kPair, kRig);
  EXPECT_FALSE(empty.SeesSomethingElse(WallPoint(150, 60)));
  const StereoCheck unmatched(pair.left, other, pair.valid, kPair, kRig);
  EXPECT_FALSE(unmatched.SeesSomethingElse(WallPoint(160, 120)));
  // Off the image, under the mask, behind the camera.
  EXPECT_FALSE(empty.SeesSomethingElse(WallPoint(2, 60)));
  EXPECT_FALSE(empty.SeesSomethingElse(WallPoint(150, 178)));
  EXPECT_FALSE(empty.SeesSomethingElse({0.0, 0.0, -1.0}));
  pair.valid.setTo(0);
  const StereoCheck masked(pair.left, pair.right, pair.valid, kPair, kRig);
  EXPECT_FALSE(masked.SeesSomethingElse(WallPoint(145, 120)));
  // A right image of another size than the left: nothing read from it. Cut from the right view
  // that shows the person, it would leave the point out if the check read it (all the row search
  // needs lies in its first 200 columns).
  const Pair fresh = MakePair(true);
  const StereoCheck whole(fresh.left, fresh.right, fresh.valid, kPair, kRig);
  ASSERT_TRUE(whole.SeesSomethingElse(WallPoint(145, 120)));
  const cv::Mat narrower = fresh.right(cv::Rect(0, 0, 200, kPair.height)).clone();
  const StereoCheck mismatched(fresh.left, narrower, fresh.valid, kPair, kRig);
  EXPECT_FALSE(mismatched.SeesSomethingElse(WallPoint(145, 120)));
}

TEST(StereoCheck, RegistrationDrawsInPlaceOfThePointsLeftOut) {
  std::vector<Eigen::Vector3d> map;
  for (int i = 0; i < 500; ++i)
    map.push_back({0.01 * i, 0.0, 2.0});
  TrackingConfig config;
  config.max_points = 200;
  config.batch_size = 100;
  const Registration plain(map, kPair, config, 5);
  const Registration all(map, kPair, config, 5, [](const Eigen::Vector3d&) { return true; });
  EXPECT_EQ(plain.points(), all.points());  // keeping all: the same draw
  EXPECT_EQ(all.left_out(), 0);
  // Points with x ≥ 3 m left out: the subset still has max_points, none of them.
  const Registration some(map, kPair, config, 5,
                          [](const Eigen::Vector3d& p) { return p.x() < 3.0; });
  ASSERT_EQ(some.size(), 200u);
  for (const Eigen::Vector3d& p : some.points())
    EXPECT_LT(p.x(), 3.0);
  EXPECT_GT(some.left_out(), 0);
  // Too few kept: all of them, and every other point counted.
  const Registration few(map, kPair, config, 5,
                         [](const Eigen::Vector3d& p) { return p.x() < 0.5; });
  EXPECT_EQ(few.size(), 50u);
  EXPECT_EQ(few.left_out(), 450);
}

// The tracker asks the pair when the check is on and it has the rig: the wall points behind the
// person are left out of the registration, none without the person or with the check off.
TEST(StereoCheck, TrackerLeavesOutThePointsBehindAPerson) {
  auto map = std::make_shared<TrackingMap>();
  for (int v = 20; v <= 160; v += 10)
    for (int u = 15; u <= 225; u += 10)
      map->points_world.push_back(WallPoint(u, v));
  const testing::Images seen = testing::Render(map->points_world, geometry::RigidTransform());
  auto left_out = [&](bool check_on, bool with_person, bool with_rig) {
    TrackingConfig config;
    config.stereo_check = check_on;
    Tracker tracker(kPair, config, imu::ImuConfig{}, geometry::RigidTransform{}, 1,
                    with_rig ? std::optional(kRig) : std::nullopt);
    tracker.Reset(0, geometry::RigidTransform());
    tracker.SetMap(map);
    const Pair pair = MakePair(with_person);
    events::Observation obs;
    obs.t_ns = 10 * kNsPerMs;
    obs.ts_left = pair.left;
    obs.ts_right = pair.right;
    obs.negative_ts_left = seen.negative;
    obs.grad_u = seen.du;
    obs.grad_v = seen.dv;
    const std::vector<imu::ImuSample> still = {
        {0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()},
        {20 * kNsPerMs, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
    const TrackingResult r = tracker.Track(obs, seen.valid, still);
    EXPECT_TRUE(r.registered);
    return r.stereo_left_out;
  };
  // The person covers left columns 100–190: the 9 of the map's 22 columns there (135 points), all
  // but those whose patch reaches past the person's edges (columns 105 and 185) at least.
  const int behind = left_out(true, true, true);
  EXPECT_GE(behind, 105);
  EXPECT_LE(behind, 135);
  EXPECT_EQ(left_out(true, false, true), 0);
  EXPECT_EQ(left_out(false, true, true), 0);
  EXPECT_EQ(left_out(true, true, false), 0);
}

}  // namespace
}  // namespace aavio::tracking
