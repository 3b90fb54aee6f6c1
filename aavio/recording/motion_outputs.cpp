#include "aavio/recording/motion_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "aavio/geometry/velocity.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/trajectory_writing.hpp"
#include "aavio/recording/run_files.hpp"

namespace aavio::recording {

namespace fs = std::filesystem;

nlohmann::json WriteMotion(const MotionOutputs& what,
                           const std::vector<geometry::StampedPose>& trajectory,
                           const std::optional<imu::GravityDirection>& gravity,
                           const Eigen::Matrix3d& R_out_first, std::vector<Status>* failures) {
  auto keep = [failures](Status status) {
    if (!status.ok()) failures->push_back(std::move(status));
  };
  nlohmann::json j = nlohmann::json::object();
  if (trajectory.empty()) return j;
  const fs::path out(what.out_dir);
  const std::vector<geometry::StampedVelocity> velocities =
      geometry::EstimateVelocities(trajectory, geometry::kDefaultVelocityHalfWindowNs);
  keep(io::WriteTextFile((out / run_files::kVelocity).string(), io::FormatVelocities(velocities)));
  std::vector<double> speeds, turn_rates;
  for (const geometry::StampedVelocity& v : velocities) {
    if (!v.valid) continue;
    speeds.push_back(v.v_body_mps.norm());
    turn_rates.push_back(v.w_body_radps.norm() * 180.0 / M_PI);
  }
  if (!speeds.empty()) {
    auto median = [](std::vector<double> x) {
      std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
      return x[x.size() / 2];
    };
    j["speed_median_mps"] = median(speeds);
    j["speed_max_mps"] = *std::max_element(speeds.begin(), speeds.end());
    j["turn_rate_median_dps"] = median(turn_rates);
  }
  if (gravity) {
    // In the world the files are in (z up already in a gravity world: q_up_world the identity).
    imu::GravityDirection g = *gravity;
    g.down_world = R_out_first * g.down_world;
    const Eigen::Quaterniond q(g.R_up_world());
    j["gravity"] = {{"down_world", {g.down_world.x(), g.down_world.y(), g.down_world.z()}},
                    {"magnitude_m_s2", g.magnitude_m_s2},
                    {"span_s", g.span_s},
                    {"q_up_world_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
  }
  if (what.format == io::TrajectoryFormat::kTum && what.poses_at.empty()) return j;
  const fs::path path = out / io::TrajectoryFileName(what.format);
  if (what.poses_at.empty()) {
    keep(io::WriteTrajectory(path.string(), trajectory, velocities, what.format));
    return j;
  }
  const geometry::Sampled sampled = geometry::SampleAt(trajectory, velocities, what.poses_at);
  keep(io::WriteTrajectory(path.string(), sampled.poses, sampled.velocities, what.format));
  j["poses_at"] = {{"requested", what.poses_at.size()},
                   {"written", sampled.poses.size()},
                   {"missing", sampled.missing.size()},
                   {"file", path.filename().string()}};
  if (!sampled.missing.empty()) {
    j["poses_at"]["first_missing_s"] = NsToSeconds(sampled.missing.front());
    j["poses_at"]["last_missing_s"] = NsToSeconds(sampled.missing.back());
  }
  return j;
}

}  // namespace aavio::recording
