#include "aavio/io/formats/ros2_bag/ros2_bag.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>

#include "aavio/common/format.hpp"
#include "aavio/io/decoded_stream_impl.hpp"
#include "aavio/io/event_codecs.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/formats/ros2_bag/mcap_file.hpp"

namespace aavio::io {

namespace {

namespace fs = std::filesystem;

constexpr const char* kEventPacketType = "event_camera_msgs/msg/EventPacket";

/// The storage files of a bag given as a .db3 / .mcap file or as its folder (in name order).
Expected<std::vector<std::string>> StorageFiles(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  if (!fs::exists(p, ec)) return NotFound(path + ": no such file or folder");
  if (!fs::is_directory(p, ec)) return std::vector<std::string>{path};
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(p, ec)) {
    if (e.path().extension() == ".db3" || e.path().extension() == ".mcap")
      files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty())
    return InvalidArgument(path + ": no .db3 or .mcap file in this folder: not a ROS 2 bag");
  return files;
}

/// Little-endian CDR of one EventPacket (after the 4-byte encapsulation header).
struct EventPacket {
  std::uint32_t height = 0, width = 0;
  std::uint64_t time_base = 0;
  std::string encoding;
  const unsigned char* events = nullptr;
  std::size_t event_bytes = 0;
};

class CdrReader {
 public:
  CdrReader(const unsigned char* data, std::size_t size) : data_(data), size_(size) {}
  bool U32(std::uint32_t* v) { return Fixed(4, v); }
  bool U64(std::uint64_t* v) { return Fixed(8, v); }
  bool String(std::string* s) {
    std::uint32_t n = 0;
    if (!U32(&n) || n > Left()) return false;
    s->assign(reinterpret_cast<const char*>(Here()), n > 0 ? n - 1 : 0);  // drops the NUL
    pos_ += n;
    return true;
  }
  bool Bytes(const unsigned char** p, std::size_t* n) {
    std::uint32_t count = 0;
    if (!U32(&count) || count > Left()) return false;
    *p = Here();
    *n = count;
    pos_ += count;
    return true;
  }
  bool Skip(std::size_t n) {
    if (n > Left()) return false;
    pos_ += n;
    return true;
  }

 private:
  const unsigned char* Here() const { return data_ + 4 + pos_; }
  std::size_t Left() const { return size_ - 4 - pos_; }
  template <typename T>
  bool Fixed(std::size_t bytes, T* v) {
    pos_ = (pos_ + bytes - 1) / bytes * bytes;  // CDR aligns to the primitive's size
    if (size_ < 4 + pos_ || bytes > Left()) return false;
    T x = 0;
    for (std::size_t k = 0; k < bytes; ++k)
      x |= static_cast<T>(Here()[k]) << (8 * k);
    *v = x;
    pos_ += bytes;
    return true;
  }
  const unsigned char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

Status ParseEventPacket(const unsigned char* data, std::size_t size, const std::string& where,
                        EventPacket* m) {
  if (size < 4) return InvalidArgument(where + ": a message shorter than its CDR header");
  if (data[1] != 0x01) {
    return InvalidArgument(where + ": big-endian CDR (representation 0x" +
                           StrFormat("%02X%02X", data[0], data[1]) + ") is not read");
  }
  CdrReader r(data, size);
  std::uint32_t sec = 0, nanosec = 0, is_bigendian_word = 0;
  std::string frame_id;
  std::uint64_t seq = 0;
  (void)is_bigendian_word;
  if (!r.U32(&sec) || !r.U32(&nanosec) || !r.String(&frame_id) || !r.U32(&m->height) ||
      !r.U32(&m->width) || !r.U64(&seq) || !r.U64(&m->time_base) || !r.String(&m->encoding) ||
      !r.Skip(1) || !r.Bytes(&m->events, &m->event_bytes)) {
    return InvalidArgument(where + ": the EventPacket is truncated or malformed");
  }
  return Status::Ok();
}

Expected<EventEncoding> ParseEncoding(const std::string& encoding, const std::string& where) {
  if (encoding == "evt3") return EventEncoding::kEvt3;
  if (encoding == "libcaer") return EventEncoding::kLibcaer;
  if (encoding == "libcaer_cmp") return EventEncoding::kLibcaerCmp;
  return InvalidArgument(where + ": event encoding '" + encoding +
                         "' is not read (aavio reads evt3, libcaer and libcaer_cmp packets)");
}

/// One storage file of the bag: its EventPacket topics, and their messages in time order.
class Storage {
 public:
  virtual ~Storage() = default;
  /// EventPacket topics: (id, name).
  virtual Expected<std::vector<std::pair<std::int64_t, std::string>>> EventTopics() = 0;
  virtual Status Query(std::int64_t topic_id) = 0;
  /// The next message of the queried topic, or false at the end.
  virtual Expected<bool> Next(const unsigned char** data, std::size_t* size,
                              std::int64_t* bag_ns) = 0;
  virtual std::int64_t index() const = 0;
  virtual const std::string& path() const = 0;
  virtual const char* kind() const = 0;
};

/// One sqlite3 file of the bag.
class Db final : public Storage {
 public:
  ~Db() override {
    if (stmt_) sqlite3_finalize(stmt_);
    if (db_) sqlite3_close(db_);
  }
  Status Open(const std::string& path) {
    AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "ROS 2 bag storage file"));
    path_ = path;
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
      return IoError(path + ": cannot open as sqlite3 (" + sqlite3_errmsg(db_) + ")");
    }
    return Status::Ok();
  }
  Expected<std::vector<std::pair<std::int64_t, std::string>>> EventTopics() override {
    sqlite3_stmt* q = nullptr;
    if (sqlite3_prepare_v2(db_, "SELECT id, name, type FROM topics", -1, &q, nullptr) !=
        SQLITE_OK) {
      return InvalidArgument(path_ + ": not a ROS 2 bag (" + sqlite3_errmsg(db_) + ")");
    }
    std::vector<std::pair<std::int64_t, std::string>> topics;
    while (sqlite3_step(q) == SQLITE_ROW) {
      const char* type = reinterpret_cast<const char*>(sqlite3_column_text(q, 2));
      if (type && std::strcmp(type, kEventPacketType) == 0) {
        const char* name = reinterpret_cast<const char*>(sqlite3_column_text(q, 1));
        if (!name) {
          const std::int64_t id = sqlite3_column_int64(q, 0);
          sqlite3_finalize(q);
          return InvalidArgument(path_ + ": the topics table's event topic of id " +
                                 std::to_string(id) +
                                 " has no name: the bag is corrupt; record it again, or give the "
                                 "topic its name in the topics table");
        }
        topics.emplace_back(sqlite3_column_int64(q, 0), name);
      }
    }
    sqlite3_finalize(q);
    return topics;
  }
  Status Query(std::int64_t topic_id) override {
    if (stmt_) sqlite3_finalize(stmt_);
    stmt_ = nullptr;
    if (sqlite3_prepare_v2(db_,
                           "SELECT timestamp, data FROM messages WHERE topic_id = ? "
                           "ORDER BY timestamp, id",
                           -1, &stmt_, nullptr) != SQLITE_OK) {
      return InvalidArgument(path_ + ": not a ROS 2 bag (" + sqlite3_errmsg(db_) + ")");
    }
    sqlite3_bind_int64(stmt_, 1, topic_id);
    index_ = 0;
    return Status::Ok();
  }
  Expected<bool> Next(const unsigned char** data, std::size_t* size,
                      std::int64_t* bag_ns) override {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_DONE) return false;
    if (rc != SQLITE_ROW) return IoError(path_ + ": read error (" + sqlite3_errmsg(db_) + ")");
    *bag_ns = sqlite3_column_int64(stmt_, 0);
    *data = static_cast<const unsigned char*>(sqlite3_column_blob(stmt_, 1));
    *size = static_cast<std::size_t>(sqlite3_column_bytes(stmt_, 1));
    ++index_;
    return true;
  }
  std::int64_t index() const override { return index_; }
  const std::string& path() const override { return path_; }
  const char* kind() const override { return "sqlite3"; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* stmt_ = nullptr;
  std::int64_t index_ = 0;
};

/// One MCAP file of the bag (ROS 2 messages in CDR).
class McapStorage final : public Storage {
 public:
  explicit McapStorage(std::unique_ptr<McapReader> reader) : r_(std::move(reader)) {}
  Expected<std::vector<std::pair<std::int64_t, std::string>>> EventTopics() override {
    std::vector<std::pair<std::int64_t, std::string>> topics;
    for (const McapReader::Channel& c : r_->channels())
      if (c.schema_name == kEventPacketType && c.message_encoding == "cdr")
        topics.emplace_back(c.id, c.topic);
    return topics;
  }
  Status Query(std::int64_t topic_id) override {
    r_->Rewind();
    channel_ = topic_id;
    index_ = 0;
    return Status::Ok();
  }
  Expected<bool> Next(const unsigned char** data, std::size_t* size,
                      std::int64_t* bag_ns) override {
    McapReader::Message m;
    while (true) {
      Expected<bool> more = r_->Next(&m);
      if (!more || !*more) return more;
      if (m.channel != channel_) continue;
      *data = m.data;
      *size = m.size;
      *bag_ns = static_cast<std::int64_t>(m.log_time_ns);
      ++index_;
      return true;
    }
  }
  std::int64_t index() const override { return index_; }
  const std::string& path() const override { return r_->path(); }
  const char* kind() const override { return "mcap"; }

 private:
  std::unique_ptr<McapReader> r_;
  std::int64_t channel_ = -1, index_ = 0;
};

Expected<std::unique_ptr<Storage>> OpenStorage(const std::string& file) {
  if (fs::path(file).extension() == ".mcap") {
    Expected<std::unique_ptr<McapReader>> r = McapReader::Open(file);
    if (!r) return r.status();
    return std::unique_ptr<Storage>(std::make_unique<McapStorage>(std::move(*r)));
  }
  auto db = std::make_unique<Db>();
  AAVIO_RETURN_IF_ERROR(db->Open(file));
  return std::unique_ptr<Storage>(std::move(db));
}

}  // namespace

struct Ros2BagEventDecoder {
  std::string path, topic;
  std::vector<std::unique_ptr<Storage>> files;
  std::vector<std::int64_t> topic_ids;  // per file
  std::size_t file = 0;
  std::optional<EventWordDecoder> decoder;
  StreamInfo info;
  ReorderBuffer<events::Event> reorder{0};
  bool exhausted = false;

  Status Rewind() {
    file = 0;
    exhausted = false;
    decoder.reset();
    return files[0]->Query(topic_ids[0]);
  }
  /// Decodes the next packet; `emit(event, where)`.
  template <typename Emit>
  Status NextPacket(Emit&& emit) {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
    std::int64_t bag_ns = 0;
    while (true) {
      Expected<bool> more = files[file]->Next(&data, &size, &bag_ns);
      if (!more) return more.status();
      if (*more) break;
      if (++file == files.size()) {
        exhausted = true;
        return Status::Ok();
      }
      AAVIO_RETURN_IF_ERROR(files[file]->Query(topic_ids[file]));
    }
    const std::string where =
        StrFormat("%s: message %lld of %s", files[file]->path().c_str(),
                  static_cast<long long>(files[file]->index()), topic.c_str());
    EventPacket packet;
    AAVIO_RETURN_IF_ERROR(ParseEventPacket(data, size, where, &packet));
    if (!decoder) {
      Expected<EventEncoding> encoding = ParseEncoding(packet.encoding, where);
      if (!encoding) return encoding.status();
      decoder.emplace(*encoding, info.width, info.height, where);
    }
    decoder->SetTimeBase(packet.time_base);
    return decoder->Decode(packet.events, packet.event_bytes, 0,
                           [&](const events::Event& e, std::int64_t) { emit(e, where); });
  }

  Status ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out) {
    Status pushed = Status::Ok();
    while (!reorder.CanRelease(t_end_ns) && !exhausted && pushed.ok()) {
      AAVIO_RETURN_IF_ERROR(NextPacket([&](const events::Event& e, const std::string& where) {
        if (pushed.ok()) pushed = reorder.Push(e, where);
      }));
    }
    AAVIO_RETURN_IF_ERROR(pushed);
    reorder.Release(t_end_ns, out);
    return Status::Ok();
  }
  Status Seek(TimeNs t_ns) {
    AAVIO_RETURN_IF_ERROR(Rewind());
    reorder.Reset(t_ns);
    return Status::Ok();
  }
  bool AtEnd() const { return exhausted && reorder.size() == 0; }
};

template class DecodedStream<events::Event, Ros2BagEventDecoder>;

Expected<std::vector<Ros2EventTopic>> ListRos2EventTopics(const std::string& path) {
  Expected<std::vector<std::string>> files = StorageFiles(path);
  if (!files) return files.status();
  Expected<std::unique_ptr<Storage>> opened = OpenStorage(files->front());
  if (!opened) return opened.status();
  Storage& db = **opened;
  auto topics = db.EventTopics();
  if (!topics) return topics.status();
  std::vector<Ros2EventTopic> out;
  for (const auto& [id, name] : *topics) {
    Ros2EventTopic t;
    t.name = name;
    AAVIO_RETURN_IF_ERROR(db.Query(id));
    const unsigned char* data = nullptr;
    std::size_t size = 0;
    std::int64_t bag_ns = 0;
    while (true) {
      Expected<bool> more = db.Next(&data, &size, &bag_ns);
      if (!more) return more.status();
      if (!*more) break;
      if (t.messages++ == 0) {
        EventPacket packet;
        AAVIO_RETURN_IF_ERROR(ParseEventPacket(data, size, path, &packet));
        t.encoding = packet.encoding;
      }
    }
    out.push_back(t);
  }
  return out;
}

Ros2BagEventStream::~Ros2BagEventStream() = default;

Expected<std::unique_ptr<Ros2BagEventStream>> Ros2BagEventStream::Open(
    const std::string& path, const std::string& topic, const StreamOptions& options) {
  Expected<std::vector<std::string>> files = StorageFiles(path);
  if (!files) return files.status();
  auto s = std::make_unique<Ros2BagEventDecoder>();
  s->path = path;
  for (const std::string& f : *files) {
    Expected<std::unique_ptr<Storage>> opened = OpenStorage(f);
    if (!opened) return opened.status();
    std::unique_ptr<Storage> db = std::move(*opened);
    auto topics = db->EventTopics();
    if (!topics) return topics.status();
    std::string names;
    for (const auto& [id, name] : *topics)
      names += (names.empty() ? "" : ", ") + name;
    std::int64_t id = -1;
    if (topic.empty()) {
      if (topics->size() != 1) {
        return InvalidArgument(f + ": " +
                               (topics->empty()
                                    ? "no " + std::string(kEventPacketType) + " topic"
                                    : "several event topics (" + names + "): name one"));
      }
      id = topics->front().first;
      s->topic = topics->front().second;
    } else {
      for (const auto& [tid, name] : *topics)
        if (name == topic) id = tid;
      if (id < 0) {
        return NotFound(f + ": no EventPacket topic '" + topic + "'" +
                        (names.empty() ? "" : "; its event topics: " + names));
      }
      s->topic = topic;
    }
    s->topic_ids.push_back(id);
    s->files.push_back(std::move(db));
  }
  // The sensor size from the first packet (or the caller's), then one pass for the info.
  s->info.width = options.width;
  s->info.height = options.height;
  AAVIO_RETURN_IF_ERROR(s->Rewind());
  {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
    std::int64_t bag_ns = 0;
    Expected<bool> first = s->files[0]->Next(&data, &size, &bag_ns);
    if (!first) return first.status();
    if (*first && options.width == 0) {
      EventPacket packet;
      AAVIO_RETURN_IF_ERROR(ParseEventPacket(
          data, size, s->files[0]->path() + ": message 1 of " + s->topic, &packet));
      s->info.width = static_cast<int>(packet.width);
      s->info.height = static_cast<int>(packet.height);
    }
  }
  AAVIO_RETURN_IF_ERROR(s->Rewind());
  std::int64_t count = 0;
  TimeNs first = 0, last = 0;
  while (!s->exhausted) {
    AAVIO_RETURN_IF_ERROR(s->NextPacket([&](const events::Event& e, const std::string&) {
      if (count++ == 0) first = last = e.t_ns;
      first = std::min(first, e.t_ns);
      last = std::max(last, e.t_ns);
    }));
  }
  s->info.count = count;
  s->info.t_first_ns = first;
  s->info.t_last_ns = last;
  s->info.description =
      std::string("ROS 2 bag (") + s->files[0]->kind() + ") EventPacket " + s->topic + ": " + path;
  s->reorder = ReorderBuffer<events::Event>(options.max_reorder_ns);
  AAVIO_RETURN_IF_ERROR(s->Rewind());
  return std::unique_ptr<Ros2BagEventStream>(new Ros2BagEventStream(std::move(s)));
}

}  // namespace aavio::io
