#include "odometry_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

#include "aavio/common/format.hpp"
#include "aavio/config/config_sources.hpp"
#include "aavio/geometry/velocity.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/formats/rosbag/rosbag_messages.hpp"
#include "aavio/pipeline/live_odometry.hpp"

namespace aavio::ros_node {
namespace {

class Engine final : public OdometryEngine {
 public:
  Engine(const EngineOptions& options, io::LoadedCalibration calibration,
         const pipeline::OdometryConfig& config, std::string describe)
      : options_(options),
        calibration_(std::move(calibration)),
        config_(config),
        describe_(std::move(describe)) {}

  ~Engine() override { (void)Finish(); }

  int width() const override { return calibration_.rig.width(); }
  int height() const override { return calibration_.rig.height(); }
  std::string Describe() const override { return describe_; }
  std::vector<std::string> warnings() const override { return calibration_.warnings; }

  bool PushEventArray(int camera, const std::string& type, const std::string& md5,
                      const std::uint8_t* data, std::size_t size, const std::string& topic,
                      std::string* error) override {
    if (type != "dvs_msgs/EventArray" && type != "dv_ros_msgs/EventArray" &&
        type != "prophesee_event_msgs/EventArray") {
      *error = topic + " carries " + type +
               "; aavio reads dvs_msgs/EventArray, dv_ros_msgs/EventArray or "
               "prophesee_event_msgs/EventArray: remap the topic to an event stream";
      return false;
    }
    if (md5 == io::rosbag::kLegacyEventArrayMd5) {
      *error = topic + ": the pre-2017 dvs_msgs/EventArray (uint64 times) is not supported";
      return false;
    }
    std::vector<events::Event> batch;
    io::rosbag::EventArrayHeader header;
    if (!io::rosbag::DecodeEventArray({data, size}, &header, &batch)) {
      *error =
          StrFormat("%s: a malformed %s message (%zu bytes)", topic.c_str(), type.c_str(), size);
      return false;
    }
    if (batch.empty()) return true;
    std::lock_guard<std::mutex> guard(mutex_);
    if (!Start(batch.front().t_ns, error)) return false;
    // The other camera's first array may begin a little before the start: those events go.
    std::erase_if(batch, [this](const events::Event& e) { return e.t_ns < start_ns_; });
    return Check(
        live_->PushEvents(camera == 0 ? events::Camera::kLeft : events::Camera::kRight, batch),
        error);
  }

  bool PushImu(const ImuReading& r, std::string* error) override {
    imu::ImuSample s;
    s.t_ns = r.t_ns;
    s.gyro_rad_s = {r.gyro_rad_s[0], r.gyro_rad_s[1], r.gyro_rad_s[2]};
    s.accel_m_s2 = {r.accel_m_s2[0], r.accel_m_s2[1], r.accel_m_s2[2]};
    std::lock_guard<std::mutex> guard(mutex_);
    if (!live_) {
      early_imu_.push_back(s);  // before the first events
      return true;
    }
    if (s.t_ns < start_ns_) return true;
    return Check(live_->PushImu({&s, 1}), error);
  }

  std::string Finish() override {
    std::lock_guard<std::mutex> guard(mutex_);
    if (!live_ || finished_) return "";
    finished_ = true;
    const Status s = live_->Finish();
    const pipeline::LiveStats st = live_->stats();
    return StrFormat(
        "%lld ticks run, %lld skipped, %lld mapping cycles skipped; events %lld + "
        "%lld, all processed: %s%s",
        static_cast<long long>(st.ticks), static_cast<long long>(st.skipped_ticks),
        static_cast<long long>(st.skipped_mapping_cycles),
        static_cast<long long>(st.events_pushed[0]), static_cast<long long>(st.events_pushed[1]),
        st.events_processed == st.events_pushed ? "yes" : "no",
        s.ok() ? "" : ("; " + s.message()).c_str());
  }

 private:
  static bool Check(const Status& s, std::string* error) {
    if (!s.ok()) *error = s.message();
    return s.ok();
  }

  bool Start(TimeNs t_ns, std::string* error) {
    if (live_) return true;
    Expected<std::unique_ptr<pipeline::LiveOdometry>> live =
        pipeline::LiveOdometry::Create(calibration_.rig, config_, t_ns,
                                       {.real_time = options_.real_time,
                                        .max_lag_s = options_.max_lag_s,
                                        .wait_for_imu = options_.use_imu});
    if (!live) return Check(live.status(), error);
    live_ = std::move(*live);
    start_ns_ = t_ns;
    live_->on_tick = [this](const pipeline::OdometryTick& tick) { Output(tick); };
    std::vector<imu::ImuSample> early;
    for (const imu::ImuSample& s : early_imu_)
      if (s.t_ns >= t_ns) early.push_back(s);
    early_imu_.clear();
    return Check(live_->PushImu(early), error);
  }

  void Output(const pipeline::OdometryTick& tick) {
    if (!on_tick) return;
    TickOutput out;
    out.t_ns = tick.t_ns;
    const Eigen::Quaterniond q = tick.T_world_cam.Quaternion();
    out.position = {tick.T_world_cam.t.x(), tick.T_world_cam.t.y(), tick.T_world_cam.t.z()};
    out.quaternion = {q.x(), q.y(), q.z(), q.w()};
    out.tracked = tick.status == tracking::TrackingStatus::kOk;
    // The twist: from the recent poses, restarted where the map was (the pose jumps there).
    if (tick.reinitialised) recent_.clear();
    recent_.push_back({tick.t_ns, tick.T_world_cam});
    while (recent_.size() > 2 &&
           tick.t_ns - recent_.front().t_ns > geometry::kDefaultVelocityHalfWindowNs)
      recent_.erase(recent_.begin());
    const geometry::StampedVelocity twist =
        geometry::NewestVelocity(recent_, geometry::kDefaultVelocityHalfWindowNs);
    if (twist.valid) {
      for (int k = 0; k < 3; ++k) {
        out.linear_mps[k] = twist.v_body_mps[k];
        out.angular_radps[k] = twist.w_body_radps[k];
      }
    }
    if (tick.map) {
      const mapping::LocalMap& map = *tick.map;
      out.has_map = true;
      out.map_confirmed = map.confirmed;
      out.map_t_ns = map.t_ns;
      out.map_points_world.reserve(3 * map.points_world.size());
      for (const Eigen::Vector3d& p : map.points_world)
        for (int k = 0; k < 3; ++k)
          out.map_points_world.push_back(static_cast<float>(p[k]));
      const int w = width(), h = height();
      out.map_depth_m.assign(static_cast<std::size_t>(w) * h,
                             std::numeric_limits<float>::quiet_NaN());
      for (const mapping::DepthPoint& p : map.points) {
        const int u = static_cast<int>(std::lround(p.u)), v = static_cast<int>(std::lround(p.v));
        if (u < 0 || v < 0 || u >= w || v >= h || !(p.rho > 0.0)) continue;
        out.map_depth_m[static_cast<std::size_t>(v) * w + u] = static_cast<float>(1.0 / p.rho);
      }
    }
    on_tick(out);
  }

  EngineOptions options_;
  io::LoadedCalibration calibration_;
  pipeline::OdometryConfig config_;
  std::string describe_;
  std::mutex mutex_;
  std::unique_ptr<pipeline::LiveOdometry> live_;
  std::vector<imu::ImuSample> early_imu_;
  std::vector<geometry::StampedPose> recent_;  // the poses of the last window, for the twist
  TimeNs start_ns_ = 0;
  bool finished_ = false;
};

}  // namespace

std::unique_ptr<OdometryEngine> OdometryEngine::Create(const EngineOptions& options,
                                                       std::string* error) {
  if (options.calib_dir.empty()) {
    *error =
        "set ~calib_dir to the calibration: an ESVO folder (left.yaml + right.yaml) or a "
        "DSEC cam_to_cam.yaml";
    return nullptr;
  }
  Expected<io::LoadedCalibration> calibration = io::LoadCalibration(options.calib_dir);
  if (!calibration) {
    *error = calibration.status().message();
    return nullptr;
  }
  config::ConfigSources sources;
  sources.preset = options.preset;
  if (!options.config_file.empty()) sources.files.push_back(options.config_file);
  sources.overrides = options.overrides;
  const std::string why = config::ConfigureForRig(calibration->rig, &sources);
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(sources);
  if (!config) {
    *error = config.status().message();
    return nullptr;
  }
  const geometry::StereoRig& rig = calibration->rig;
  const std::string describe =
      StrFormat("%dx%d rig, f %.1f px, baseline %.3f m; %s%s%s", rig.width(), rig.height(),
                rig.focal_px(), rig.baseline_m(), config::DescribeSources(sources).c_str(),
                why.empty() ? "" : ": ", why.c_str());
  return std::make_unique<Engine>(options, std::move(*calibration), *config, describe);
}

}  // namespace aavio::ros_node
