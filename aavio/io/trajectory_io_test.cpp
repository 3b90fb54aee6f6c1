#include "aavio/io/trajectory_io.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

TEST(TumTrajectory, ReadsWhitespaceCommasAndComments) {
  const std::string text =
      "# timestamp tx ty tz qx qy qz qw\n"
      "\n"
      "1518196259.772284031 0.726453324 -1.519792664 -0.665759173 0 0 0 1\n"
      "1518196259.777284031,0.1,0.2,0.3,0,0,0.7071068,0.7071068\r\n"
      "  1518196259.782284031\t1 2 3   0 0 2.71051e-20 1  \n";
  Expected<std::vector<geometry::StampedPose>> poses = ParseTumTrajectory(text, "gt.txt");
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 3u);
  EXPECT_EQ((*poses)[0].t_ns, 1518196259772284031LL);  // all 19 digits kept
  EXPECT_EQ((*poses)[1].t_ns, 1518196259777284031LL);
  EXPECT_NEAR((*poses)[0].T_world_body.t.y(), -1.519792664, 1e-15);
  EXPECT_NEAR(geometry::LogSO3((*poses)[1].T_world_body.R).norm(), M_PI / 2, 1e-6);
}

TEST(TumTrajectory, WriteReadRoundTripIsExact) {
  std::vector<geometry::StampedPose> poses;
  for (int i = 0; i < 50; ++i) {
    geometry::StampedPose p;
    p.t_ns = 36470774788442LL + i * 10'000'001LL;
    p.T_world_body = {geometry::ExpSO3(Eigen::Vector3d(0.01 * i, -0.3, 0.02 * i)),
                      Eigen::Vector3d(0.1 * i, -2.0, 1e-3 * i)};
    poses.push_back(p);
  }
  const std::string path = (testing::ScratchDir() / "stamped_traj_estimate.txt").string();
  ASSERT_TRUE(WriteTumTrajectory(path, poses).ok());
  ASSERT_TRUE(WriteTumTrajectory(path, poses).ok());  // truncates, never appends
  Expected<std::vector<geometry::StampedPose>> back = ReadTumTrajectory(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_EQ(back->size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ((*back)[i].t_ns, poses[i].t_ns);
    EXPECT_LT(((*back)[i].T_world_body.t - poses[i].T_world_body.t).norm(), 1e-9);
    EXPECT_LT(geometry::RotationDistance((*back)[i].T_world_body.R, poses[i].T_world_body.R), 1e-8);
  }
  const std::string text = FormatTumTrajectory({poses[0]});
  EXPECT_EQ(text,
            "# timestamp tx ty tz qx qy qz qw\n36470.774788442 0.000000000 -2.000000000 "
            "0.000000000 0.000000000 -0.149438132 0.000000000 0.988771078\n");
}

TEST(TumTrajectory, MalformedLinesGiveFileAndLine) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n", "t.txt:2: expected 8 columns"},
      {"1 0 0 0 0 0 0 1\nabc 0 0 0 0 0 0 1\n", "t.txt:2: 'abc' is not a time in seconds"},
      {"1 0 0 x 0 0 0 1\n", "t.txt:1: tz = 'x' is not a finite number"},
      {"1 0 0 0 0 0 0 2\n", "t.txt:1: the quaternion has norm 2"},
      {"# c\n2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n",
       "t.txt:3: timestamp 1 is before the one on line 2"},
      {"1 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n", "t.txt:2: timestamp 1.0 repeats"},
      {"1 0 0 0 0 0 0 nan\n", "qw = 'nan' is not a finite number"},
  };
  for (const Case& c : cases) {
    Expected<std::vector<geometry::StampedPose>> poses = ParseTumTrajectory(c.text, "t.txt");
    ASSERT_FALSE(poses.ok()) << c.text;
    EXPECT_NE(poses.status().message().find(c.expected), std::string::npos)
        << poses.status().message();
  }
  EXPECT_EQ(ReadTumTrajectory("/nonexistent.txt").status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(ParseTumTrajectory("# only a comment\n", "t.txt")->empty());
}

// The same two poses in each layout a user brings, read with the format told from the data.
TEST(Trajectory, FormatsAreToldApartFromTheData) {
  // At 1.5 s and 1.6 s (from an epoch of 1 700 000 000 s where stamps are absolute): x 1 -> 2,
  // turned 90 degrees about z at the second.
  const double h = std::sqrt(0.5);
  struct Case {
    std::string text;
    TrajectoryFormat format;
    TimeNs t0_ns;
  };
  const std::vector<Case> cases = {
      {"# timestamp tx ty tz qx qy qz qw\n1.5 1 0 0 0 0 0 1\n1.6 2 0 0 0 0 " + std::to_string(h) +
           " " + std::to_string(h) + "\n",
       TrajectoryFormat::kTum, 1'500'000'000},
      {"1500000000 1 0 0 0 0 0 1\n1600000000 2 0 0 0 0 " + std::to_string(h) + " " +
           std::to_string(h) + "\n",
       TrajectoryFormat::kTumNs, 1'500'000'000},
      {"1700000001500000000 1 0 0 0 0 0 1\n1700000001600000000 2 0 0 0 0 " + std::to_string(h) +
           " " + std::to_string(h) + "\n",
       TrajectoryFormat::kTumNs, 1'700'000'001'500'000'000},
      {"#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],"
       "q_RS_z []\n1500000000,1,0,0,1,0,0,0\n1600000000,2,0,0," +
           std::to_string(h) + ",0,0," + std::to_string(h) + "\n",
       TrajectoryFormat::kEuroc, 1'500'000'000},
      // EuRoC's state estimate: velocity and biases after the pose, no header.
      {"1500000000,1,0,0,1,0,0,0,0.1,0,0,0,0,0,0,0,0\n1600000000,2,0,0," + std::to_string(h) +
           ",0,0," + std::to_string(h) + ",0.1,0,0,0,0,0,0,0,0\n",
       TrajectoryFormat::kEuroc, 1'500'000'000},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    Expected<std::vector<geometry::StampedPose>> auto_read =
        ParseTrajectory(c.text, "t.txt", TrajectoryFormat::kAuto);
    ASSERT_TRUE(auto_read.ok()) << auto_read.status().message();
    Expected<std::vector<geometry::StampedPose>> forced =
        ParseTrajectory(c.text, "t.txt", c.format);
    ASSERT_TRUE(forced.ok()) << forced.status().message();
    ASSERT_EQ(auto_read->size(), 2u);
    EXPECT_EQ((*auto_read)[0].t_ns, c.t0_ns);
    EXPECT_EQ((*auto_read)[1].t_ns - (*auto_read)[0].t_ns, 100'000'000);
    EXPECT_NEAR((*auto_read)[1].T_world_body.t.x(), 2.0, 1e-12);
    EXPECT_NEAR(geometry::RotationDistance(
                    (*auto_read)[1].T_world_body.R,
                    Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()),
                0.0, 1e-5);
    EXPECT_EQ((*forced)[1].t_ns, (*auto_read)[1].t_ns);
  }
  // KITTI has no stamps: they come beside it, or line by line; a name that is no format is said
  // with the list.
  const std::string kitti = "1 0 0 0 0 1 0 0 0 0 1 0\n0 -1 0 1.5 1 0 0 0 0 0 1 0\n";
  const Status no_stamps = ParseTrajectory(kitti, "k.txt", TrajectoryFormat::kAuto).status();
  EXPECT_NE(no_stamps.message().find("k.txt: a KITTI pose file (12 columns) has no timestamps; "
                                     "give its times.txt with --times"),
            std::string::npos)
      << no_stamps.message();
  const std::vector<TimeNs> stamps = {1'000'000'000, 1'100'000'000};
  Expected<TrajectoryFile> with_stamps =
      ParseTrajectoryFile(kitti, "k.txt", TrajectoryFormat::kAuto, &stamps);
  ASSERT_TRUE(with_stamps.ok()) << with_stamps.status().message();
  EXPECT_EQ(with_stamps->format, TrajectoryFormat::kKitti);
  EXPECT_EQ(with_stamps->poses[1].t_ns, 1'100'000'000);
  EXPECT_NEAR(with_stamps->poses[1].T_world_body.t.x(), 1.5, 1e-12);
  EXPECT_NEAR(with_stamps->poses[1].T_world_body.R(1, 0), 1.0, 1e-12);
  const std::vector<TimeNs> by_line;
  EXPECT_EQ(ParseTrajectoryFile(kitti, "k.txt", TrajectoryFormat::kKitti, &by_line)->poses[1].t_ns,
            100'000'000);
  const std::vector<TimeNs> one = {5};
  EXPECT_NE(ParseTrajectoryFile(kitti, "k.txt", TrajectoryFormat::kKitti, &one)
                .status()
                .message()
                .find("more poses than the 1 stamps"),
            std::string::npos);
  EXPECT_NE(
      ParseTrajectoryFile("2 0 0 0 0 1 0 0 0 0 1 0\n", "k.txt", TrajectoryFormat::kKitti, &by_line)
          .status()
          .message()
          .find("not a rotation"),
      std::string::npos);
  // EvSLAM gives a velocity per pose.
  Expected<TrajectoryFile> evslam =
      ParseTrajectoryFile("0.5 1 2 3 0 0 0 1 0.1 0.2 0.3\n0.6 1 2 3 0 0 0 1 0.1 0.2 0.4\n", "e.txt",
                          TrajectoryFormat::kAuto);
  ASSERT_TRUE(evslam.ok()) << evslam.status().message();
  EXPECT_EQ(evslam->format, TrajectoryFormat::kEvslam);
  ASSERT_EQ(evslam->v_body_mps.size(), 2u);
  EXPECT_DOUBLE_EQ(evslam->v_body_mps[1].z(), 0.4);
  EXPECT_NE(TrajectoryFormatNamed("g2o").status().message().find("none of auto, tum"),
            std::string::npos);
  EXPECT_EQ(*TrajectoryFormatNamed("euroc"), TrajectoryFormat::kEuroc);
}

}  // namespace
}  // namespace aavio::io
