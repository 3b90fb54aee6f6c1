#include "aavio/recording/timings_csv.hpp"

#include "aavio/common/format.hpp"

namespace aavio::recording {
namespace {

// The IMU columns: the gyroscope bias the tick used [rad/s], and with the IMU back-end
// (imu.mode=full, once solved) its accelerometer bias [m/s²] and gravity in the world [m/s²].
std::string ImuColumns(const pipeline::OdometryTick& t) {
  std::string out = StrFormat("%.6g,%.6g,%.6g", t.gyro_bias.x(), t.gyro_bias.y(), t.gyro_bias.z());
  if (!t.imu_state) return out + ",,,,,,";
  const imu::ImuState& s = *t.imu_state;
  return out + StrFormat(",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", s.accel_bias.x(), s.accel_bias.y(),
                         s.accel_bias.z(), s.gravity_world.x(), s.gravity_world.y(),
                         s.gravity_world.z());
}

}  // namespace

Status TimingsCsv::Add(const pipeline::OdometryTick& t, double mapping_ms) {
  if (!csv_.is_open()) {
    csv_.open(path_);
    csv_ << "t_s,status,time_surface_ms,aa_ms,sampling_ms,tracking_ms,iterations,mapping_ms,"
            "map_points,lost_reason,events,gyro_bias_x,gyro_bias_y,gyro_bias_z,accel_bias_x,"
            "accel_bias_y,accel_bias_z,gravity_x,gravity_y,gravity_z\n";
  }
  csv_ << StrFormat(
      "%.6f,%s,%.4f,%.4f,%.4f,%.4f,%d,%.4f,%zu,%s,%lld,%s\n", NsToSeconds(t.t_ns),
      tracking::TrackingStatusName(t.status), t.representation.time_surface_ms,
      t.representation.aa_ms, t.representation.sampling_ms, t.tracking_ms,
      t.registration_iterations, mapping_ms, t.map ? t.map->points.size() : 0,
      t.status == tracking::TrackingStatus::kLost ? tracking::LostReasonName(t.lost_reason) : "",
      static_cast<long long>(events_since_tick_), ImuColumns(t).c_str());
  events_since_tick_ = 0;
  if (!csv_) return IoError(path_ + ": write failed (disk full?)");
  return Status::Ok();
}

Status TimingsCsv::Close() {
  if (!csv_.is_open()) return Status::Ok();
  csv_.close();
  if (!csv_) return IoError(path_ + ": write failed (disk full?)");
  return Status::Ok();
}

}  // namespace aavio::recording
