#include <gtest/gtest.h>

#include "aavio/io/calibration.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

using testing::Replace;
using testing::ScratchDir;
using testing::WriteFile;

/// Writes a left/right pair into a fresh folder and loads the folder.
Expected<LoadedCalibration> LoadPair(const std::string& left, const std::string& right) {
  const auto dir = ScratchDir();
  WriteFile(dir / "left.yaml", left);
  WriteFile(dir / "right.yaml", right);
  return LoadCalibration(dir.string());
}

std::string ErrorOf(const std::string& left, const std::string& right) {
  Expected<LoadedCalibration> c = LoadPair(left, right);
  EXPECT_FALSE(c.ok());
  return c.ok() ? std::string() : c.status().message();
}

TEST(EsvoCalibration, LoadsTheRpgPair) {
  Expected<LoadedCalibration> c = LoadPair(testing::kRpgLeftYaml, testing::kRpgRightYaml);
  ASSERT_TRUE(c.ok()) << c.status().message();
  const geometry::StereoRig& rig = c->rig;
  EXPECT_EQ(c->format, "esvo");
  EXPECT_EQ(rig.width(), 240);
  EXPECT_EQ(rig.height(), 180);
  EXPECT_DOUBLE_EQ(rig.focal_px(), 156.925);
  EXPECT_NEAR(rig.baseline_m(), 0.14805, 1e-5);  // docs/tracking.md
  EXPECT_EQ(rig.left().model(), geometry::DistortionModel::kRadtan);
  EXPECT_DOUBLE_EQ(rig.left().intrinsics().coeffs[0], -0.336733);
  EXPECT_NEAR(rig.T_right_left().t.x(), -0.1479883582369969, 1e-15);
  ASSERT_TRUE(rig.T_imu_left().has_value());
  EXPECT_LT(geometry::LogSO3(rig.T_imu_left()->R).norm(), 0.02);
  EXPECT_TRUE(c->warnings.empty());
}

TEST(EsvoCalibration, EitherFileFindsItsPartner) {
  const auto dir = ScratchDir();
  WriteFile(dir / "left.yaml", testing::kRpgLeftYaml);
  WriteFile(dir / "right.yaml", testing::kRpgRightYaml);
  for (const char* name : {"left.yaml", "right.yaml"}) {
    Expected<LoadedCalibration> c = LoadCalibration((dir / name).string());
    ASSERT_TRUE(c.ok()) << c.status().message();
    EXPECT_EQ(c->files[0], (dir / "left.yaml").string());
  }
  std::filesystem::remove(dir / "right.yaml");
  Expected<LoadedCalibration> c = LoadCalibration((dir / "left.yaml").string());
  EXPECT_NE(c.status().message().find("right.yaml does not exist"), std::string::npos);
}

// ESVO2's DSEC calibration: T_right_left declares 3x4 but lists 9 numbers.
TEST(EsvoCalibration, DerivesTheExtrinsicFromNineNumbersWithAWarning) {
  Expected<LoadedCalibration> c = LoadPair(testing::kDsecLeftYaml, testing::kDsecRightYaml);
  ASSERT_TRUE(c.ok()) << c.status().message();
  const geometry::StereoRig& rig = c->rig;
  EXPECT_NEAR(rig.baseline_m(), 321.1164388243399 / 536.0578704071853, 1e-12);  // 0.599 m
  ASSERT_EQ(c->warnings.size(), 1u);
  EXPECT_NE(c->warnings[0].find("declares 3x4 but holds 9 numbers"), std::string::npos);
  EXPECT_NE(c->warnings[0].find("left.yaml:"), std::string::npos);
  // The derived extrinsic rectifies exactly: R_rectR · R_RL · R_rectLᵀ = I, R_rectR · t = (−b,0,0).
  const Eigen::Matrix3d I =
      rig.R_rect_right_right() * rig.T_right_left().R * rig.R_rect_left_left().transpose();
  EXPECT_LT(geometry::LogSO3(I).norm(), 1e-12);
  EXPECT_LT(
      (rig.R_rect_right_right() * rig.T_right_left().t - Eigen::Vector3d(-rig.baseline_m(), 0, 0))
          .norm(),
      1e-12);
  // The file's own 9 numbers agree with the derivation (the warning reports the angle).
  EXPECT_NE(c->warnings[0].find("differs from it by 0.00"), std::string::npos);
  // T_b_c = diag(−1, −1, 1): a 180° rotation about z.
  EXPECT_NEAR(geometry::LogSO3(rig.T_imu_left()->R).norm(), M_PI, 1e-9);
}

TEST(EsvoCalibration, RefusesMalformedFilesWithPreciseMessages) {
  const std::string L = testing::kRpgLeftYaml;
  const std::string R = testing::kRpgRightYaml;
  struct Case {
    std::string left, right, expected;
  };
  const std::vector<Case> cases = {
      // cols 4 but 6 values: no reading of them is the obvious one.
      {Replace(L, "data: [-0.336733, 0.111789, -0.00140053, -0.000459594]",
               "data: [-0.336733, 0.111789, -0.00140053, -0.000459594, 0.0, 0.0]"),
       R,
       "left.yaml:10: distortion_coefficients declares rows x cols = 1x4 = 4 values but its "
       "data lists 6; if the data are right, set cols: 6"},
      // 5 values under 1x4 for an equidistant camera (4 coefficients): ambiguous, refused.
      {Replace(Replace(L, "data: [-0.336733, 0.111789, -0.00140053, -0.000459594]",
                       "data: [-0.336733, 0.111789, -0.00140053, -0.000459594, 0.0]"),
               "distortion_model: plumb_bob", "distortion_model: equidistant"),
       R,
       "left.yaml:10: distortion_coefficients declares rows x cols = 1x4 = 4 values but its "
       "data lists 5"},
      {Replace(L, "image_height: 180\n", ""), R, "left.yaml: missing key 'image_height'"},
      {L, Replace(R, "projection_matrix:", "projection:"),
       "right.yaml: missing key 'projection_matrix'"},
      {Replace(L, "rows: 3\n  cols: 3\n  data: [196.639", "rows: 3\n  cols: 4\n  data: [196.639"),
       R, "camera_matrix declares rows x cols = 3x4 = 12 values but its data lists 9"},
      {Replace(L, "data: [0.999791, -0.018779", "data: [0.5, -0.018779"), R,
       "left.yaml: rectification_matrix is not a rotation"},
      {Replace(L, "image_width: 240", "image_width: two hundred"), R,
       "left.yaml:1: image_width = 'two hundred' is not an integer"},
      {Replace(L, "196.639, 0, 105.064", "-196.639, 0, 105.064"), R,
       "focal lengths must be positive"},
      {Replace(L, "distortion_model: plumb_bob", "distortion_model: rational_polynomial"), R,
       "distortion_model 'rational_polynomial' is not supported"},
      {L, Replace(R, "108.167, -23.2327", "108.167, 23.2327"), "swap the left and right files"},
      {L, Replace(R, "data: [196.426", "data: [abc"),
       "right.yaml:7: camera_matrix.data[0] = 'abc' is not a finite number"},
      {Replace(L, "0.00632456886338, 0.00935904469797, 0.99993620202, 0]",
               "0.00632456886338, 0.00935904469797, -0.99993620202, 0]"),
       R, "left.yaml: T_b_c rotation is a reflection"},
      {L, Replace(R, "image_width: 240", "image_width: 320"), "image sizes differ"},
      // ESVO v1's DSEC file: a value of T_right_left's third row duplicated (not a rotation).
      {Replace(L, "-0.010059803423311134, 0.0010362522169301642",
               "-0.010059803423311134, -0.010059803423311134"),
       R, "T_right_left rotation is not a rotation"},
      {"image_width: [240\n", R, "left.yaml:2:1: YAML syntax error"},
      {"", R, "left.yaml: file is empty"},
      {"- just\n- a list\n", R, "expected a mapping of keys at the top level"},
  };
  for (const Case& c : cases) {
    const std::string message = ErrorOf(c.left, c.right);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected: " << c.expected << "\n got: " << message;
  }
}

// VECtor's published files: plumb_bob with 5 values under a 1x4 header. The one reading of five
// plumb_bob values is k1 k2 p1 p2 k3; the file loads, and a warning says what was assumed.
TEST(EsvoCalibration, ReadsFivePlumbBobValuesUnderAFourColumnHeaderWithAWarning) {
  const std::string left =
      Replace(testing::kRpgLeftYaml, "data: [-0.336733, 0.111789, -0.00140053, -0.000459594]",
              "data: [-0.336733, 0.111789, -0.00140053, -0.000459594, 0.0125]");
  Expected<LoadedCalibration> c = LoadPair(left, testing::kRpgRightYaml);
  ASSERT_TRUE(c.ok()) << c.status().message();
  const std::vector<double>& k = c->rig.left().intrinsics().coeffs;
  ASSERT_EQ(k.size(), 5u);
  EXPECT_DOUBLE_EQ(k[4], 0.0125);
  ASSERT_EQ(c->warnings.size(), 1u);
  EXPECT_NE(c->warnings[0].find("left.yaml:10: distortion_coefficients declares 1x4 but lists 5 "
                                "values; read them as plumb_bob k1 k2 p1 p2 k3 (k3 = 0.0125)"),
            std::string::npos)
      << c->warnings[0];
  // The same file with the header put right loads identically, without the warning.
  Expected<LoadedCalibration> fixed =
      LoadPair(Replace(left, "rows: 1\n  cols: 4", "rows: 1\n  cols: 5"), testing::kRpgRightYaml);
  ASSERT_TRUE(fixed.ok()) << fixed.status().message();
  EXPECT_TRUE(fixed->warnings.empty());
  EXPECT_EQ(fixed->rig.left().intrinsics().coeffs, k);
}

TEST(EsvoCalibration, MissingExtrinsicIsDerivedWithAWarning) {
  const std::string L = testing::kRpgLeftYaml;
  const std::string left = L.substr(0, L.find("T_right_left:"));
  Expected<LoadedCalibration> c = LoadPair(left, testing::kRpgRightYaml);
  ASSERT_TRUE(c.ok()) << c.status().message();
  ASSERT_FALSE(c->warnings.empty());
  EXPECT_NE(c->warnings[0].find("no T_right_left"), std::string::npos);
  EXPECT_FALSE(c->rig.T_imu_left().has_value());
}

TEST(Calibration, UnknownPathsAndLayouts) {
  EXPECT_EQ(LoadCalibration("/nonexistent/calib").status().code(), StatusCode::kNotFound);
  const auto dir = ScratchDir();
  EXPECT_NE(LoadCalibration(dir.string()).status().message().find("no calibration here"),
            std::string::npos);
  const std::string other = WriteFile(dir / "camera.yaml", "foo: 1\n");
  EXPECT_NE(LoadCalibration(other).status().message().find("not a calibration aavio knows"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::io

namespace aavio::io {
namespace {

TEST(EsvoCalibration, WrittenCalibrationLoadsBackIdentically) {
  Expected<LoadedCalibration> original = LoadPair(testing::kRpgLeftYaml, testing::kRpgRightYaml);
  ASSERT_TRUE(original.ok());
  const auto dir = testing::ScratchDir() / "calib";
  ASSERT_TRUE(WriteEsvoCalibration(dir.string(), original->rig).ok());
  Expected<LoadedCalibration> back = LoadCalibration(dir.string());
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_TRUE(back->warnings.empty());
  const geometry::StereoRig& a = original->rig;
  const geometry::StereoRig& b = back->rig;
  EXPECT_EQ(a.P_right(), b.P_right());
  EXPECT_LT((a.R_rect_left_left() - b.R_rect_left_left()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(a.left().intrinsics().coeffs, b.left().intrinsics().coeffs);
  EXPECT_LT((a.T_right_left().Matrix() - b.T_right_left().Matrix()).cwiseAbs().maxCoeff(), 1e-15);
  ASSERT_TRUE(b.T_imu_left().has_value());
  EXPECT_LT((a.T_imu_left()->R - b.T_imu_left()->R).cwiseAbs().maxCoeff(), 1e-15);
  // A folder cannot be made under a regular file (whatever the user's permissions).
  const std::string file = testing::WriteFile(testing::ScratchDir() / "file.txt", "x");
  EXPECT_FALSE(WriteEsvoCalibration(file + "/calib", a).ok());
}

}  // namespace
}  // namespace aavio::io
