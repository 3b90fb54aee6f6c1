#include "aavio/io/formats/rosbag/bag_writer.hpp"

#include <bzlib.h>
#include <lz4frame.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "aavio/io/formats/rosbag/rosbag_messages.hpp"

namespace aavio::io {

namespace {

constexpr std::uint8_t kOpMessage = 0x02, kOpBagHeader = 0x03, kOpIndex = 0x04, kOpChunk = 0x05,
                       kOpChunkInfo = 0x06, kOpConnection = 0x07;
constexpr std::size_t kBagHeaderSize = 4096;  // the bag header record is padded to this

void PutBytes(std::vector<std::uint8_t>* out, const void* data, std::size_t n) {
  const std::size_t at = out->size();
  out->resize(at + n);
  if (n > 0) std::memcpy(out->data() + at, data, n);
}

void PutU32(std::vector<std::uint8_t>* out, std::uint32_t v) {
  PutBytes(out, &v, 4);
}

/// Builds a record header from name=value fields.
class FieldList {
 public:
  FieldList& Add(const std::string& name, const void* value, std::size_t n) {
    PutU32(&bytes_, static_cast<std::uint32_t>(name.size() + 1 + n));
    PutBytes(&bytes_, name.data(), name.size());
    bytes_.push_back('=');
    PutBytes(&bytes_, value, n);
    return *this;
  }
  FieldList& Op(std::uint8_t op) { return Add("op", &op, 1); }
  FieldList& U32(const std::string& name, std::uint32_t v) { return Add(name, &v, 4); }
  FieldList& U64(const std::string& name, std::uint64_t v) { return Add(name, &v, 8); }
  FieldList& Time(const std::string& name, TimeNs t) {
    const std::uint32_t v[2] = {static_cast<std::uint32_t>(t / kNsPerS),
                                static_cast<std::uint32_t>(t % kNsPerS)};
    return Add(name, v, 8);
  }
  FieldList& Str(const std::string& name, const std::string& s) {
    return Add(name, s.data(), s.size());
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

void AppendRecord(std::vector<std::uint8_t>* out, const FieldList& header,
                  std::span<const std::uint8_t> data) {
  PutU32(out, static_cast<std::uint32_t>(header.bytes().size()));
  PutBytes(out, header.bytes().data(), header.bytes().size());
  PutU32(out, static_cast<std::uint32_t>(data.size()));
  PutBytes(out, data.data(), data.size());
}

struct ConnectionInfo {
  std::uint32_t id;
  std::string topic;
  const rosbag::MessageType* type;
  std::uint32_t seq = 0;
};

struct PendingPacket {
  bool open = false;
  std::int64_t index = 0;  // packet k covers [k·P, (k+1)·P)
  std::vector<events::Event> events;
  TimeNs last_t_ns = std::numeric_limits<TimeNs>::min();
};

}  // namespace

struct BagWriter::State {
  std::string path;
  BagWriterOptions options;
  std::FILE* file = nullptr;
  std::uint64_t position = 0;
  std::map<std::string, ConnectionInfo> connections;  // by topic
  std::vector<const ConnectionInfo*> connection_order;
  // The open chunk: uncompressed records, and per connection (time, offset) index entries.
  std::vector<std::uint8_t> chunk;
  std::map<std::uint32_t, std::vector<std::pair<TimeNs, std::uint32_t>>> chunk_index;
  TimeNs chunk_start = 0, chunk_end = 0;
  struct Info {
    std::uint64_t position;
    TimeNs start, end;
    std::map<std::uint32_t, std::uint32_t> counts;
  };
  std::vector<Info> chunk_infos;
  std::map<std::string, PendingPacket> packets;
  std::vector<std::uint8_t> message;
  bool closed = false;

  Status WriteBytes(std::span<const std::uint8_t> bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) {
      return IoError(path + ": write failed (disk full?)");
    }
    position += bytes.size();
    return Status::Ok();
  }

  const ConnectionInfo& Connection(const std::string& topic, const rosbag::MessageType& type) {
    auto it = connections.find(topic);
    if (it == connections.end()) {
      ConnectionInfo info{static_cast<std::uint32_t>(connections.size()), topic, &type};
      it = connections.emplace(topic, info).first;
      connection_order.push_back(&it->second);
      // The connection record goes into the chunk that first uses it (and into the index).
      AppendRecord(&chunk, ConnectionHeader(it->second), ConnectionData(it->second));
    }
    return it->second;
  }

  static FieldList ConnectionHeader(const ConnectionInfo& c) {
    FieldList h;
    h.Op(kOpConnection).U32("conn", c.id).Str("topic", c.topic);
    return h;
  }
  static std::vector<std::uint8_t> ConnectionData(const ConnectionInfo& c) {
    FieldList d;
    d.Str("topic", c.topic)
        .Str("type", c.type->name)
        .Str("md5sum", c.type->md5sum)
        .Str("message_definition", c.type->definition);
    return d.bytes();
  }

  Status AddMessage(const ConnectionInfo& c, TimeNs t, std::span<const std::uint8_t> data) {
    if (chunk_index.empty()) {
      chunk_start = chunk_end = t;
    }
    chunk_start = std::min(chunk_start, t);
    chunk_end = std::max(chunk_end, t);
    chunk_index[c.id].emplace_back(t, static_cast<std::uint32_t>(chunk.size()));
    FieldList h;
    h.Op(kOpMessage).U32("conn", c.id).Time("time", t);
    AppendRecord(&chunk, h, data);
    if (chunk.size() >= options.chunk_bytes) return FlushChunk();
    return Status::Ok();
  }

  Status FlushChunk() {
    if (chunk_index.empty()) return Status::Ok();
    std::vector<std::uint8_t> compressed;
    std::string name = "none";
    std::span<const std::uint8_t> payload = chunk;
    if (options.compression == BagCompression::kLz4) {
      name = "lz4";
      // The frame settings ROS's own roslz4 writes (and requires to read): independent 1 MB
      // blocks and a content checksum.
      LZ4F_preferences_t prefs{};
      prefs.frameInfo.blockSizeID = LZ4F_max1MB;
      prefs.frameInfo.blockMode = LZ4F_blockIndependent;
      prefs.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
      compressed.resize(LZ4F_compressFrameBound(chunk.size(), &prefs));
      const std::size_t n = LZ4F_compressFrame(compressed.data(), compressed.size(), chunk.data(),
                                               chunk.size(), &prefs);
      if (LZ4F_isError(n)) return IoError(path + ": lz4 compression failed");
      compressed.resize(n);
      payload = compressed;
    } else if (options.compression == BagCompression::kBz2) {
      name = "bz2";
      unsigned int n = static_cast<unsigned int>(chunk.size() + chunk.size() / 100 + 600);
      compressed.resize(n);
      if (BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(compressed.data()), &n,
                                   reinterpret_cast<char*>(chunk.data()),
                                   static_cast<unsigned int>(chunk.size()), 9, 0, 30) != BZ_OK) {
        return IoError(path + ": bz2 compression failed");
      }
      compressed.resize(n);
      payload = compressed;
    }
    Info info{position, chunk_start, chunk_end, {}};
    std::vector<std::uint8_t> out;
    FieldList h;
    h.Op(kOpChunk).Str("compression", name).U32("size", static_cast<std::uint32_t>(chunk.size()));
    AppendRecord(&out, h, payload);
    // Index data records follow each chunk: (time, offset) of each message per connection.
    for (const auto& [id, entries] : chunk_index) {
      std::vector<std::uint8_t> data;
      for (const auto& [t, offset] : entries) {
        const std::uint32_t time[2] = {static_cast<std::uint32_t>(t / kNsPerS),
                                       static_cast<std::uint32_t>(t % kNsPerS)};
        PutBytes(&data, time, 8);
        PutU32(&data, offset);
      }
      FieldList ih;
      ih.Op(kOpIndex)
          .U32("ver", 1)
          .U32("conn", id)
          .U32("count", static_cast<std::uint32_t>(entries.size()));
      AppendRecord(&out, ih, data);
      info.counts[id] = static_cast<std::uint32_t>(entries.size());
    }
    AAVIO_RETURN_IF_ERROR(WriteBytes(out));
    chunk_infos.push_back(std::move(info));
    chunk.clear();
    chunk_index.clear();
    return Status::Ok();
  }

  Status EmitPacket(const std::string& topic, PendingPacket* packet) {
    const ConnectionInfo& c = Connection(topic, rosbag::kEventArray);
    const TimeNs stamp = (packet->index + 1) * options.event_packet_ns;
    rosbag::EncodeEventArray(stamp, connections.at(topic).seq++, "",
                             static_cast<std::uint32_t>(options.width),
                             static_cast<std::uint32_t>(options.height), packet->events, &message);
    packet->events.clear();
    packet->open = false;
    return AddMessage(c, stamp, message);
  }

  std::vector<std::uint8_t> BagHeader(std::uint64_t index_pos) const {
    FieldList h;
    h.Op(kOpBagHeader)
        .U64("index_pos", index_pos)
        .U32("conn_count", static_cast<std::uint32_t>(connections.size()))
        .U32("chunk_count", static_cast<std::uint32_t>(chunk_infos.size()));
    const std::size_t used = 4 + h.bytes().size() + 4;
    std::vector<std::uint8_t> padding(kBagHeaderSize - used, ' ');
    std::vector<std::uint8_t> out;
    AppendRecord(&out, h, padding);
    return out;
  }
};

BagWriter::BagWriter(std::unique_ptr<State> s) : s_(std::move(s)) {}

BagWriter::~BagWriter() {
  if (s_ && !s_->closed) (void)Close();
}

Expected<std::unique_ptr<BagWriter>> BagWriter::Create(const std::string& path,
                                                       const BagWriterOptions& options) {
  if (options.event_packet_ns <= 0 || options.chunk_bytes == 0) {
    return InvalidArgument(path + ": event_packet_ns and chunk_bytes must be positive");
  }
  auto s = std::make_unique<State>();
  s->path = path;
  s->options = options;
  s->file = std::fopen(path.c_str(), "wb");
  if (!s->file) return IoError(path + ": cannot open for writing");
  const std::string magic = "#ROSBAG V2.0\n";
  AAVIO_RETURN_IF_ERROR(
      s->WriteBytes(std::span(reinterpret_cast<const std::uint8_t*>(magic.data()), magic.size())));
  AAVIO_RETURN_IF_ERROR(s->WriteBytes(s->BagHeader(0)));  // rewritten by Close
  return std::unique_ptr<BagWriter>(new BagWriter(std::move(s)));
}

Status BagWriter::WriteEvents(const std::string& topic, std::span<const events::Event> events) {
  State& s = *s_;
  if (s.closed) return FailedPrecondition(s.path + ": writer already closed");
  PendingPacket& packet = s.packets[topic];
  for (const events::Event& e : events) {
    if (e.t_ns < packet.last_t_ns) {
      return InvalidArgument(s.path + ": events of " + topic +
                             " must be written in time order (event at " + FormatSecondsNs(e.t_ns) +
                             " s after one at " + FormatSecondsNs(packet.last_t_ns) + " s)");
    }
    if (e.t_ns < 0)
      return InvalidArgument(s.path + ": negative timestamps cannot be stored in a bag");
    const std::int64_t index = e.t_ns / s.options.event_packet_ns;
    if (packet.open && index != packet.index) AAVIO_RETURN_IF_ERROR(s.EmitPacket(topic, &packet));
    packet.open = true;
    packet.index = index;
    packet.events.push_back(e);
    packet.last_t_ns = e.t_ns;
  }
  return Status::Ok();
}

Status BagWriter::WriteImu(const std::string& topic, const imu::ImuSample& sample) {
  State& s = *s_;
  if (s.closed) return FailedPrecondition(s.path + ": writer already closed");
  const ConnectionInfo& c = s.Connection(topic, rosbag::kImu);
  rosbag::EncodeImu(sample, s.connections.at(topic).seq++, "imu", &s.message);
  return s.AddMessage(c, sample.t_ns, s.message);
}

Status BagWriter::WritePose(const std::string& topic, const geometry::StampedPose& pose) {
  State& s = *s_;
  if (s.closed) return FailedPrecondition(s.path + ": writer already closed");
  const ConnectionInfo& c = s.Connection(topic, rosbag::kPoseStamped);
  rosbag::EncodePoseStamped(pose, s.connections.at(topic).seq++, "world", &s.message);
  return s.AddMessage(c, pose.t_ns, s.message);
}

Status BagWriter::Close() {
  State& s = *s_;
  if (s.closed) return Status::Ok();
  s.closed = true;
  Status status = [&]() -> Status {
    for (auto& [topic, packet] : s.packets) {
      if (packet.open) AAVIO_RETURN_IF_ERROR(s.EmitPacket(topic, &packet));
    }
    AAVIO_RETURN_IF_ERROR(s.FlushChunk());
    const std::uint64_t index_pos = s.position;
    std::vector<std::uint8_t> index;
    for (const ConnectionInfo* c : s.connection_order) {
      AppendRecord(&index, State::ConnectionHeader(*c), State::ConnectionData(*c));
    }
    for (const State::Info& info : s.chunk_infos) {
      std::vector<std::uint8_t> data;
      for (const auto& [id, count] : info.counts) {
        PutU32(&data, id);
        PutU32(&data, count);
      }
      FieldList h;
      h.Op(kOpChunkInfo)
          .U32("ver", 1)
          .U64("chunk_pos", info.position)
          .Time("start_time", info.start)
          .Time("end_time", info.end)
          .U32("count", static_cast<std::uint32_t>(info.counts.size()));
      AppendRecord(&index, h, data);
    }
    AAVIO_RETURN_IF_ERROR(s.WriteBytes(index));
    const std::vector<std::uint8_t> header = s.BagHeader(index_pos);
    if (std::fseek(s.file, 13, SEEK_SET) != 0 ||
        std::fwrite(header.data(), 1, header.size(), s.file) != header.size()) {
      return IoError(s.path + ": cannot write the bag header");
    }
    return Status::Ok();
  }();
  const bool closed_ok = std::fclose(s.file) == 0;
  s.file = nullptr;
  if (!status.ok()) return status;
  return closed_ok ? Status::Ok() : IoError(s.path + ": closing failed (disk full?)");
}

}  // namespace aavio::io
