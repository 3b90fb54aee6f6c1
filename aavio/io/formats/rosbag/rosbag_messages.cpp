#include "aavio/io/formats/rosbag/rosbag_messages.hpp"

#include <cstring>

namespace aavio::io::rosbag {

namespace {

#define AAVIO_SEPARATOR \
  "================================================================================\n"
#define AAVIO_HEADER_DEF "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"

}  // namespace

const MessageType kEventArray = {
    "dvs_msgs/EventArray", "5e8beee5a6c107e504c2e78903c224b8",
    "Header header\nuint32 height\nuint32 width\nEvent[] events\n" AAVIO_SEPARATOR AAVIO_HEADER_DEF
        AAVIO_SEPARATOR "MSG: dvs_msgs/Event\nuint16 x\nuint16 y\ntime ts\nbool polarity\n"};

const MessageType kImu = {
    "sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2",
    "Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
    "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
    "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] "
    "linear_acceleration_covariance\n" AAVIO_SEPARATOR AAVIO_HEADER_DEF AAVIO_SEPARATOR
    "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n" AAVIO_SEPARATOR
    "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n"};

const MessageType kPoseStamped = {
    "geometry_msgs/PoseStamped", "d3812c3cbc69362b77dc0b19b345f8f5",
    "Header header\ngeometry_msgs/Pose pose\n" AAVIO_SEPARATOR AAVIO_HEADER_DEF AAVIO_SEPARATOR
    "MSG: geometry_msgs/Pose\ngeometry_msgs/Point position\ngeometry_msgs/Quaternion "
    "orientation\n" AAVIO_SEPARATOR
    "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" AAVIO_SEPARATOR
    "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"};

#undef AAVIO_SEPARATOR
#undef AAVIO_HEADER_DEF

namespace {

/// Bounds-checked little-endian reading.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> data) : data_(data) {}
  template <typename T>
  bool Get(T* value) {
    if (data_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(value, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool Time(TimeNs* t) {
    std::uint32_t sec = 0, nsec = 0;
    if (!Get(&sec) || !Get(&nsec) || nsec >= 1'000'000'000u) return false;
    *t = static_cast<TimeNs>(sec) * kNsPerS + nsec;
    return true;
  }
  bool SkipString() {
    std::uint32_t len = 0;
    if (!Get(&len) || data_.size() - pos_ < len) return false;
    pos_ += len;
    return true;
  }
  bool Header(TimeNs* stamp) {
    std::uint32_t seq = 0;
    return Get(&seq) && Time(stamp) && SkipString();
  }
  std::size_t remaining() const { return data_.size() - pos_; }
  const std::uint8_t* here() const { return data_.data() + pos_; }

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
};

class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>* out) : out_(out) { out_->clear(); }
  template <typename T>
  void Put(T value) {
    const std::size_t at = out_->size();
    out_->resize(at + sizeof(T));
    std::memcpy(out_->data() + at, &value, sizeof(T));
  }
  void Time(TimeNs t) {
    Put(static_cast<std::uint32_t>(t / kNsPerS));
    Put(static_cast<std::uint32_t>(t % kNsPerS));
  }
  void Header(std::uint32_t seq, TimeNs stamp, const std::string& frame_id) {
    Put(seq);
    Time(stamp);
    Put(static_cast<std::uint32_t>(frame_id.size()));
    const std::size_t at = out_->size();
    out_->resize(at + frame_id.size());
    if (!frame_id.empty()) std::memcpy(out_->data() + at, frame_id.data(), frame_id.size());
  }

 private:
  std::vector<std::uint8_t>* out_;
};

}  // namespace

bool DecodeEventArray(std::span<const std::uint8_t> data, EventArrayHeader* header,
                      std::vector<events::Event>* out) {
  Reader r(data);
  std::uint32_t count = 0;
  if (!r.Header(&header->stamp_ns) || !r.Get(&header->height) || !r.Get(&header->width) ||
      !r.Get(&count) || r.remaining() != 13ull * count) {
    return false;
  }
  const std::uint8_t* p = r.here();
  const std::size_t begin = out->size();
  out->resize(begin + count);
  for (std::uint32_t i = 0; i < count; ++i, p += 13) {
    std::uint16_t x, y;
    std::uint32_t sec, nsec;
    std::memcpy(&x, p, 2);
    std::memcpy(&y, p + 2, 2);
    std::memcpy(&sec, p + 4, 4);
    std::memcpy(&nsec, p + 8, 4);
    if (nsec >= 1'000'000'000u) {
      out->resize(begin);
      return false;
    }
    (*out)[begin + i] = {static_cast<TimeNs>(sec) * kNsPerS + nsec, x, y,
                         static_cast<std::uint8_t>(p[12] ? 1 : 0)};
  }
  return true;
}

bool DecodeImu(std::span<const std::uint8_t> data, imu::ImuSample* out) {
  Reader r(data);
  double v[37];
  if (!r.Header(&out->t_ns)) return false;
  for (double& x : v) {
    if (!r.Get(&x)) return false;
  }
  // orientation (4), its covariance (9), angular velocity (3), covariance (9), linear accel (3).
  out->gyro_rad_s = {v[13], v[14], v[15]};
  out->accel_m_s2 = {v[25], v[26], v[27]};
  return r.remaining() == 0;
}

bool DecodePoseStamped(std::span<const std::uint8_t> data, geometry::StampedPose* out) {
  Reader r(data);
  double v[7];
  if (!r.Header(&out->t_ns)) return false;
  for (double& x : v) {
    if (!r.Get(&x)) return false;
  }
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (r.remaining() != 0 || !(q.norm() > 0.5)) return false;
  out->T_world_body = {q.normalized().toRotationMatrix(), Eigen::Vector3d(v[0], v[1], v[2])};
  return true;
}

void EncodeEventArray(TimeNs stamp_ns, std::uint32_t seq, const std::string& frame_id,
                      std::uint32_t width, std::uint32_t height,
                      std::span<const events::Event> events, std::vector<std::uint8_t>* out) {
  Writer w(out);
  w.Header(seq, stamp_ns, frame_id);
  w.Put(height);
  w.Put(width);
  w.Put(static_cast<std::uint32_t>(events.size()));
  out->reserve(out->size() + 13 * events.size());
  for (const events::Event& e : events) {
    w.Put(e.x);
    w.Put(e.y);
    w.Time(e.t_ns);
    w.Put(static_cast<std::uint8_t>(e.polarity ? 1 : 0));
  }
}

void EncodeImu(const imu::ImuSample& s, std::uint32_t seq, const std::string& frame_id,
               std::vector<std::uint8_t>* out) {
  Writer w(out);
  w.Header(seq, s.t_ns, frame_id);
  // No orientation: by convention orientation_covariance[0] = −1 (docs/io.md).
  for (double q : {0.0, 0.0, 0.0, 1.0})
    w.Put(q);
  for (int i = 0; i < 9; ++i)
    w.Put(i == 0 ? -1.0 : 0.0);
  for (int i = 0; i < 3; ++i)
    w.Put(s.gyro_rad_s[i]);
  for (int i = 0; i < 9; ++i)
    w.Put(0.0);
  for (int i = 0; i < 3; ++i)
    w.Put(s.accel_m_s2[i]);
  for (int i = 0; i < 9; ++i)
    w.Put(0.0);
}

void EncodePoseStamped(const geometry::StampedPose& pose, std::uint32_t seq,
                       const std::string& frame_id, std::vector<std::uint8_t>* out) {
  Writer w(out);
  w.Header(seq, pose.t_ns, frame_id);
  const Eigen::Quaterniond q = pose.T_world_body.Quaternion();
  for (int i = 0; i < 3; ++i)
    w.Put(pose.T_world_body.t[i]);
  for (double c : {q.x(), q.y(), q.z(), q.w()})
    w.Put(c);
}

}  // namespace aavio::io::rosbag
