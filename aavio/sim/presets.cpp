#include "aavio/sim/presets.hpp"

namespace aavio::sim {

namespace {

using geometry::CameraIntrinsics;
using geometry::CameraModel;
using geometry::DistortionModel;

Eigen::Matrix3d Rows(std::initializer_list<double> v) {
  Eigen::Matrix3d M;
  auto it = v.begin();
  for (int i = 0; i < 9; ++i)
    M(i / 3, i % 3) = *it++;
  return M;
}

geometry::ProjectionMatrix Projection(double f, double cx, double cy, double tx) {
  geometry::ProjectionMatrix P = geometry::ProjectionMatrix::Zero();
  P(0, 0) = P(1, 1) = f;
  P(0, 2) = cx;
  P(1, 2) = cy;
  P(2, 2) = 1.0;
  P(0, 3) = tx;
  return P;
}

/// T_right_left from the rectification when a calibration does not state it (the rule of
/// io/calibration.hpp): [R_rect_Rᵀ R_rect_L | R_rect_Rᵀ (−b, 0, 0)ᵀ].
geometry::RigidTransform FromRectification(const Eigen::Matrix3d& R_l, const Eigen::Matrix3d& R_r,
                                           double baseline_m) {
  const Eigen::Matrix3d L = geometry::Orthonormalize(R_l), R = geometry::Orthonormalize(R_r);
  return {R.transpose() * L, R.transpose() * Eigen::Vector3d(-baseline_m, 0, 0)};
}

Expected<geometry::StereoRig> Make(const CameraIntrinsics& left, const CameraIntrinsics& right,
                                   const Eigen::Matrix3d& R_l, const Eigen::Matrix3d& R_r,
                                   const geometry::ProjectionMatrix& P_l,
                                   const geometry::ProjectionMatrix& P_r,
                                   const geometry::RigidTransform& T_right_left,
                                   const geometry::RigidTransform& T_imu_left) {
  Expected<CameraModel> l = CameraModel::Create(left);
  if (!l) return l.status();
  Expected<CameraModel> r = CameraModel::Create(right);
  if (!r) return r.status();
  return geometry::StereoRig::Create({*l, *r, R_l, R_r, P_l, P_r, T_right_left, T_imu_left});
}

// rpg: DAVIS240C pair, ESVO/ESVO2 calib/rpg (Zhou et al., ECCV 2018).
const CameraIntrinsics kRpgLeft{240,
                                180,
                                196.639,
                                196.733,
                                105.064,
                                72.4717,
                                DistortionModel::kRadtan,
                                {-0.336733, 0.111789, -0.00140053, -0.000459594}};
const CameraIntrinsics kRpgRight{240,
                                 180,
                                 196.426,
                                 196.564,
                                 110.745,
                                 88.1131,
                                 DistortionModel::kRadtan,
                                 {-0.346294, 0.12772, -0.000272051, -0.000195801}};
Eigen::Matrix3d RpgRectLeft() {
  return Rows({0.999791, -0.018779, -0.00802416, 0.0187767, 0.999824, -0.000360707, 0.00802952,
               0.000209964, 0.999968});
}
Eigen::Matrix3d RpgRectRight() {
  return Rows({0.999589, 0.0222217, -0.0181009, -0.0222166, 0.999753, 0.000486491, 0.0181073,
               -8.41512e-05, 0.999836});
}
geometry::RigidTransform RpgRightLeft() {
  Eigen::Matrix<double, 3, 4> T;
  T << 0.9991089760393723, -0.04098010198963204, 0.010093821797214667, -0.1479883582369969,
      0.04098846609277917, 0.9991594254283246, -0.000623077121092687, -0.003289908601915284,
      -0.010059803423311134, 0.0010362522169301642, 0.9999488619606629, 0.0026798262366239016;
  return geometry::RigidTransform::FromMatrix(T);
}
geometry::RigidTransform RpgImuLeft() {
  return {
      Rows({0.999905117246, 0.0121780171243, -0.00643835413146, -0.0122374970355, 0.999882045134,
            -0.00928113597812, 0.00632456886338, 0.00935904469797, 0.99993620202}),
      Eigen::Vector3d::Zero()};
}

Expected<geometry::StereoRig> RpgRig() {
  return Make(kRpgLeft, kRpgRight, RpgRectLeft(), RpgRectRight(),
              Projection(156.925, 108.167, 78.4205, 0.0),
              Projection(156.925, 108.167, 78.4205, -23.2327), RpgRightLeft(), RpgImuLeft());
}

/// The rpg pair scaled to 160×120 (intrinsics × 2/3; same lens, rotations and baseline).
Expected<geometry::StereoRig> MiniRig() {
  auto scale = [](CameraIntrinsics in) {
    const double s = 2.0 / 3.0;
    in.width = 160;
    in.height = 120;
    in.fx *= s;
    in.fy *= s;
    in.cx = (in.cx + 0.5) * s - 0.5;
    in.cy = (in.cy + 0.5) * s - 0.5;
    return in;
  };
  const double s = 2.0 / 3.0;
  const double f = 156.925 * s, cx = (108.167 + 0.5) * s - 0.5, cy = (78.4205 + 0.5) * s - 0.5;
  return Make(scale(kRpgLeft), scale(kRpgRight), RpgRectLeft(), RpgRectRight(),
              Projection(f, cx, cy, 0.0), Projection(f, cx, cy, -23.2327 * s), RpgRightLeft(),
              RpgImuLeft());
}

// DSEC zurich_city_04_a event pair, ESVO2 calib/dsec/zurich_city_04_a (its T_right_left holds
// only a rotation: derived from the rectification, which agrees with that rotation to 0.000°).
Expected<geometry::StereoRig> DsecRig() {
  const CameraIntrinsics left{640,
                              480,
                              553.469,
                              553.399,
                              346.653,
                              216.521,
                              DistortionModel::kRadtan,
                              {-0.0935648, 0.194458, 7.64243e-05, 0.00195639}};
  const CameraIntrinsics right{640,
                               480,
                               552.182,
                               551.445,
                               336.874,
                               226.326,
                               DistortionModel::kRadtan,
                               {-0.0949368, 0.202115, 0.000582129, 0.00145529}};
  const Eigen::Matrix3d R_l = Rows({0.999866, -0.00319364, 0.0160517, 0.00322964, 0.999992,
                                    -0.00221712, -0.0160445, 0.00226867, 0.999869});
  const Eigen::Matrix3d R_r = Rows({0.999963, 0.00818053, -0.00267849, -0.0081745, 0.999964,
                                    0.00225394, 0.00269683, -0.00223196, 0.999994});
  const double f = 536.0578704071853, cx = 336.2674980163574, cy = 222.2888011932373;
  const double tx = -321.1164388243399;
  return Make(left, right, R_l, R_r, Projection(f, cx, cy, 0.0), Projection(f, cx, cy, tx),
              FromRectification(R_l, R_r, -tx / f),
              {Rows({-1, 0, 0, 0, -1, 0, 0, 0, 1}), Eigen::Vector3d::Zero()});
}

// MVSEC DAVIS346 pair, ESVO2 calib/upenn (equidistant).
Expected<geometry::StereoRig> MvsecRig() {
  const CameraIntrinsics left{
      346,
      260,
      226.38018519795807,
      226.15002947047415,
      173.6470807871759,
      133.73271487507847,
      DistortionModel::kEquidistant,
      {-0.048031442223833355, 0.011330957517194437, -0.055378166304281135, 0.021500973881459395}};
  const CameraIntrinsics right{
      346,
      260,
      226.0181418548734,
      225.7869434267677,
      174.5433576736815,
      124.21627572590607,
      DistortionModel::kEquidistant,
      {-0.04846669832871334, 0.010092844338123635, -0.04293073765014637, 0.005194706897326005}};
  const Eigen::Matrix3d R_l =
      Rows({0.999877311526236, 0.015019439766575743, -0.004447282784398257, -0.014996983873604017,
            0.9998748347535599, 0.005040367172759556, 0.004522429630305261, -0.004973052949604937,
            0.9999774079320989});
  const Eigen::Matrix3d R_r =
      Rows({0.9999922706537476, 0.003931701344419404, -1.890238450965101e-05, -0.003931746704476347,
            0.9999797362744968, -0.005006836150689904, -7.83382948021244e-07, 0.0050068717705076754,
            0.9999874655386736});
  Eigen::Matrix<double, 3, 4> T;
  T << 0.9999285439274112, 0.011088072985503046, -0.004467849222081981, -0.09988137641750752,
      -0.011042817783611191, 0.9998887260774646, 0.01002953830336461, -0.0003927067773089277,
      0.004578560319692358, -0.009979483987103495, 0.9999397215256256, 1.8880107752680777e-06;
  const double f = 199.6530123165822, cx = 177.43276376280926, cy = 126.81215684365904;
  return Make(left, right, R_l, R_r, Projection(f, cx, cy, 0.0),
              Projection(f, cx, cy, -19.941771812941038), geometry::RigidTransform::FromMatrix(T),
              {});
}

// TUM-VIE (Klenk et al., IROS 2021), mocap-desk calibration as ESVO2 publishes it: 1280×720.
Expected<geometry::StereoRig> TumVieRig() {
  const CameraIntrinsics left{1280,
                              720,
                              1049.583,
                              1049.423,
                              634.7184,
                              263.4698,
                              DistortionModel::kEquidistant,
                              {-0.1151966, -0.06222183, 0.2168261, -0.2352862}};
  const CameraIntrinsics right{1280,
                               720,
                               1047.668,
                               1047.523,
                               652.9083,
                               260.541,
                               DistortionModel::kEquidistant,
                               {-0.1246107, 0.006075037, 0.03566192, -0.08888043}};
  const Eigen::Matrix3d R_l = Rows({0.999754826676689, -0.01266626048306591, -0.01816183861944204,
                                    0.01247096879510851, 0.9998636259452682, -0.01082610035478137,
                                    0.01829648802297759, 0.01059695036109404, 0.9997764465964727});
  const Eigen::Matrix3d R_r = Rows({0.9998695874466074, -0.01531690352425632, -0.005118648823660143,
                                    0.01537085831336992, 0.9998248945376152, 0.0106731896617947,
                                    0.004954272303945287, -0.01075047576970244, 0.999929938774044});
  Eigen::Matrix<double, 3, 4> T;
  T << 0.9999139238730244, 0.00275304520871895, -0.0128283119283708, -0.1187973925652208,
      -0.003015363491210488, 0.9997858361647609, -0.02047411505649691, 0.002000794259366445,
      0.01276919840352954, 0.02051103474741225, 0.9997080799041905, 0.0009996342780319578;
  return Make(
      left, right, R_l, R_r,
      Projection(974.8248485687409, 657.1452947326158, 249.0317449660879, 0.0),
      Projection(974.8248485687409, 665.7830960074431, 249.0317449660879, -115.4845433975721),
      geometry::RigidTransform::FromMatrix(T), {});
}

// VECtor (Gao et al., RA-L 2022), the event pair as ESVO2 publishes it (plumb_bob, k3 = 0):
// 640×480.
Expected<geometry::StereoRig> VectorRig() {
  const CameraIntrinsics left{640,
                              480,
                              327.32749,
                              327.46184,
                              304.97749,
                              235.37621,
                              DistortionModel::kRadtan,
                              {-0.031982, 0.041966, -0.000507, -0.001031}};
  const CameraIntrinsics right{640,
                               480,
                               327.48497,
                               327.55395,
                               318.53477,
                               230.96356,
                               DistortionModel::kRadtan,
                               {-0.0263, 0.037995, -0.000513, 0.000167}};
  const Eigen::Matrix3d R_l = Rows({1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0});
  const Eigen::Matrix3d R_r = Rows({1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0});
  Eigen::Matrix<double, 3, 4> T;
  T << 1.0, 0.0, 0.0, -0.17, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0;
  return Make(
      left, right, R_l, R_r,
      Projection(257.7465659912339, 317.5881580988773, 237.3116097643339, 0.0),
      Projection(257.7465659912339, 317.5881580988773, 237.3116097643339, -43.81691621850976),
      geometry::RigidTransform::FromMatrix(T), {});
}

// An iniVation DVXplorer pair (640×480, 9 µm pixels) as the EvSLAM 2026 challenge's stereo rig
// uses; its calibration is not public, so the numbers are a typical build of such a rig: a 4 mm
// lens (f 444 px, 71° across), mild radial distortion, 10 cm baseline, cameras parallel.
Expected<geometry::StereoRig> DvxplorerRig() {
  const CameraIntrinsics camera{
      640, 480, 444.0, 444.0, 321.5, 238.5, DistortionModel::kRadtan, {-0.09, 0.06, 0.0, 0.0}};
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  constexpr double kFocalRect = 430.0;  // the rectified image keeps the distorted corners out
  return Make(camera, camera, I, I, Projection(kFocalRect, 319.5, 239.5, 0.0),
              Projection(kFocalRect, 319.5, 239.5, -kFocalRect * 0.10),
              {I, Eigen::Vector3d(-0.10, 0.0, 0.0)}, {});
}

// An ideal rectified pinhole pair (no distortion, parallel cameras): f 200 px, baseline 0.15 m,
// the IMU on the left camera.
Expected<geometry::StereoRig> PinholeRig() {
  const CameraIntrinsics camera{240, 180, 200.0, 200.0, 119.5, 89.5, DistortionModel::kNone, {}};
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  return Make(camera, camera, I, I, Projection(200.0, 119.5, 89.5, 0.0),
              Projection(200.0, 119.5, 89.5, -200.0 * 0.15), {I, Eigen::Vector3d(-0.15, 0.0, 0.0)},
              {});
}

SimulationPreset Preset(std::string name, std::string description, SceneKind scene,
                        MotionKind motion, double duration_s,
                        Expected<geometry::StereoRig> (*rig)()) {
  SimulationPreset p;
  p.name = std::move(name);
  p.description = std::move(description);
  p.scene = scene;
  p.motion = motion;
  p.duration_s = duration_s;
  p.rig = rig;
  return p;
}

std::vector<SimulationPreset> AllPresets() {
  std::vector<SimulationPreset> presets;
  // DAVIS240C: threshold ~0.2–0.3 log units, background activity ~0.1 Hz per pixel.
  SimulationPreset rpg = Preset("rpg", "DAVIS240C stereo (rpg), room, hand-held 6-DoF",
                                SceneKind::kRoom, MotionKind::kHandHeld, 20.0, &RpgRig);
  rpg.events.threshold_on = rpg.events.threshold_off = 0.25;
  presets.push_back(rpg);
  // Prophesee Gen3.1: similar contrast, lower background rate, hot pixels present.
  SimulationPreset dsec = Preset("dsec", "DSEC zurich_city_04_a event pair, street canyon, driving",
                                 SceneKind::kStreet, MotionKind::kDriving, 30.0, &DsecRig);
  dsec.events.threshold_on = dsec.events.threshold_off = 0.3;
  dsec.events.noise_rate_hz = 0.05;
  dsec.events.hot_pixel_fraction = 1e-4;
  dsec.camera = CameraKind::kProphesee;
  presets.push_back(dsec);
  SimulationPreset mvsec = Preset("mvsec", "MVSEC DAVIS346 stereo (upenn), hall, drone flight",
                                  SceneKind::kHall, MotionKind::kDrone, 30.0, &MvsecRig);
  presets.push_back(mvsec);
  // Prophesee sensors, as DSEC's: Gen4 HD (TUM-VIE) and Gen3 VGA (VECtor).
  SimulationPreset tum_vie =
      Preset("tum_vie", "TUM-VIE 1280x720 event pair (mocap-desk), office, hand-held",
             SceneKind::kOffice, MotionKind::kHandHeld, 20.0, &TumVieRig);
  SimulationPreset vector = Preset("vector", "VECtor 640x480 event pair, lab, hand-held",
                                   SceneKind::kLab, MotionKind::kHandHeld, 20.0, &VectorRig);
  for (SimulationPreset* p : {&tum_vie, &vector}) {
    p->events = dsec.events;
    p->camera = CameraKind::kProphesee;
    presets.push_back(*p);
  }
  SimulationPreset dvxplorer =
      Preset("dvxplorer", "iniVation DVXplorer 640x480 pair (EvSLAM 2026 rig), hall, drone flight",
             SceneKind::kHall, MotionKind::kDrone, 20.0, &DvxplorerRig);
  dvxplorer.events = rpg.events;
  dvxplorer.camera = CameraKind::kDvxplorer;
  presets.push_back(dvxplorer);
  SimulationPreset planes =
      Preset("planes", "ideal 240x180 pinhole pair, sparse scene of textured planes, sinusoid",
             SceneKind::kPlanes, MotionKind::kSinusoid, 8.0, &PinholeRig);
  planes.events = rpg.events;
  presets.push_back(planes);
  SimulationPreset mini = Preset("mini", "rpg pair at 160x120, room, hand-held, 3 s (tests, demo)",
                                 SceneKind::kRoom, MotionKind::kHandHeld, 3.0, &MiniRig);
  mini.imu.rate_hz = 500.0;
  presets.push_back(mini);
  return presets;
}

}  // namespace

namespace {

template <typename Kind, std::size_t N>
Expected<Kind> Named(const std::string& name, const std::pair<const char*, Kind> (&table)[N],
                     const char* what) {
  std::string known;
  for (const auto& [n, kind] : table) {
    if (name == n) return kind;
    known += (known.empty() ? "" : ", ") + std::string(n);
  }
  return InvalidArgument("'" + name + "' is not a " + what + "; one of " + known);
}

}  // namespace

Expected<SceneKind> SceneKindNamed(const std::string& name) {
  static constexpr std::pair<const char*, SceneKind> kScenes[] = {
      {"room", SceneKind::kRoom}, {"office", SceneKind::kOffice}, {"lab", SceneKind::kLab},
      {"hall", SceneKind::kHall}, {"street", SceneKind::kStreet}, {"planes", SceneKind::kPlanes}};
  return Named(name, kScenes, "scene");
}

Expected<MotionKind> MotionKindNamed(const std::string& name) {
  static constexpr std::pair<const char*, MotionKind> kMotions[] = {
      {"hand_held", MotionKind::kHandHeld},
      {"driving", MotionKind::kDriving},
      {"drone", MotionKind::kDrone},
      {"sinusoid", MotionKind::kSinusoid}};
  return Named(name, kMotions, "motion");
}

std::vector<std::string> SimulationPresetNames() {
  std::vector<std::string> names;
  for (const SimulationPreset& p : AllPresets())
    names.push_back(p.name);
  return names;
}

Expected<SimulationPreset> GetSimulationPreset(const std::string& name) {
  std::string known;
  for (const SimulationPreset& p : AllPresets()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  return NotFound("no simulation preset named '" + name + "'; presets: " + known);
}

}  // namespace aavio::sim
