#include "aavio/io/formats/ros2_bag/ros2_bag.hpp"

#include <gtest/gtest.h>
#include <lz4frame.h>
#include <sqlite3.h>
#include <zstd.h>

#include <fstream>

#include "tests/little_endian.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

/// Little-endian CDR, aligned like the ROS 2 middleware writes it.
class CdrWriter {
 public:
  CdrWriter() : bytes_{0x00, 0x01, 0x00, 0x00} {}
  void U32(std::uint32_t v) { Fixed(v); }
  void U64(std::uint64_t v) { Fixed(v); }
  void String(const std::string& s) {
    U32(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }
  void Bool(bool b) { bytes_.push_back(b ? 1 : 0); }
  void Bytes(const std::vector<unsigned char>& b) {
    U32(static_cast<std::uint32_t>(b.size()));
    bytes_.insert(bytes_.end(), b.begin(), b.end());
  }
  std::vector<unsigned char> bytes_;

 private:
  template <typename T>
  void Fixed(T v) {
    while ((bytes_.size() - 4) % sizeof(T) != 0)  // CDR aligns to the size
      bytes_.push_back(0);
    testing::AppendLittleEndian(&bytes_, v);
  }
};

std::vector<unsigned char> EventPacket(const std::string& encoding, std::uint64_t time_base,
                                       const std::vector<unsigned char>& events) {
  CdrWriter w;
  w.U32(1700000000);  // stamp
  w.U32(5);
  w.String("camera");
  w.U32(480);  // height
  w.U32(640);  // width
  w.U64(7);    // seq
  w.U64(time_base);
  w.String(encoding);
  w.Bool(false);
  w.Bytes(events);
  return w.bytes_;
}

void Put16(std::vector<unsigned char>* b, unsigned w) {
  testing::AppendLittleEndian(b, static_cast<std::uint16_t>(w));
}
void Put32(std::vector<unsigned char>* b, std::uint32_t w) {
  testing::AppendLittleEndian(b, w);
}

/// A rosbag2 sqlite3 file with the tables rosbag2 writes; messages: (topic id, bag time, data).
std::string WriteBag(
    const std::string& name, const std::vector<std::pair<std::string, std::string>>& topics,
    const std::vector<std::tuple<int, std::int64_t, std::vector<unsigned char>>>& messages) {
  const std::string path = (aavio::testing::ScratchDir() / name).string();
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_exec(
      db,
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
      nullptr, nullptr, nullptr);
  for (std::size_t k = 0; k < topics.size(); ++k) {
    const std::string sql = "INSERT INTO topics VALUES(" + std::to_string(k + 1) + ", '" +
                            topics[k].first + "', '" + topics[k].second + "', 'cdr', '')";
    sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
  }
  sqlite3_stmt* insert = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1,
                     &insert, nullptr);
  for (const auto& [topic, t, data] : messages) {
    sqlite3_bind_int(insert, 1, topic);
    sqlite3_bind_int64(insert, 2, t);
    sqlite3_bind_blob(insert, 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
    sqlite3_step(insert);
    sqlite3_reset(insert);
  }
  sqlite3_finalize(insert);
  sqlite3_close(db);
  return path;
}

constexpr const char* kPacket = "event_camera_msgs/msg/EventPacket";

/// An MCAP file as the rosbag2 MCAP plugin writes it: header, schemas and channels, messages in
/// chunks (lz4, zstd or none) or alone, data end, footer.
class McapWriter {
 public:
  using Bytes = std::vector<unsigned char>;
  McapWriter() : file_{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'} {
    Bytes header;
    Str(&header, "ros2");
    Str(&header, "test");
    Record(0x01, header, &file_);
  }
  static void Str(Bytes* b, const std::string& s) {
    Int<std::uint32_t>(b, static_cast<std::uint32_t>(s.size()));
    b->insert(b->end(), s.begin(), s.end());
  }
  template <typename T>
  static void Int(Bytes* b, T v) {
    testing::AppendLittleEndian(b, v);
  }
  static void Record(std::uint8_t op, const Bytes& content, Bytes* to) {
    to->push_back(op);
    Int<std::uint64_t>(to, content.size());
    to->insert(to->end(), content.begin(), content.end());
  }
  static Bytes Schema(std::uint16_t id, const std::string& name) {
    Bytes b;
    Int(&b, id);
    Str(&b, name);
    Str(&b, "ros2msg");
    Str(&b, "# definition");
    Bytes r;
    Record(0x03, b, &r);
    return r;
  }
  static Bytes Channel(std::uint16_t id, std::uint16_t schema, const std::string& topic) {
    Bytes b;
    Int(&b, id);
    Int(&b, schema);
    Str(&b, topic);
    Str(&b, "cdr");
    Int<std::uint32_t>(&b, 0);  // no metadata
    Bytes r;
    Record(0x04, b, &r);
    return r;
  }
  static Bytes Message(std::uint16_t channel, std::uint64_t t_ns, const Bytes& data) {
    Bytes b;
    Int(&b, channel);
    Int<std::uint32_t>(&b, 0);
    Int(&b, t_ns);
    Int(&b, t_ns);
    b.insert(b.end(), data.begin(), data.end());
    Bytes r;
    Record(0x05, b, &r);
    return r;
  }
  void Append(const Bytes& records) { file_.insert(file_.end(), records.begin(), records.end()); }
  void Chunk(const Bytes& records, const std::string& compression) {
    Bytes packed = records;
    if (compression == "lz4") {
      packed.resize(LZ4F_compressFrameBound(records.size(), nullptr));
      packed.resize(LZ4F_compressFrame(packed.data(), packed.size(), records.data(), records.size(),
                                       nullptr));
    } else if (compression == "zstd") {
      packed.resize(ZSTD_compressBound(records.size()));
      packed.resize(ZSTD_compress(packed.data(), packed.size(), records.data(), records.size(), 1));
    }
    Bytes b;
    Int<std::uint64_t>(&b, 0);
    Int<std::uint64_t>(&b, 0);
    Int<std::uint64_t>(&b, records.size());
    Int<std::uint32_t>(&b, 0);  // no CRC
    Str(&b, compression);
    Int<std::uint64_t>(&b, packed.size());
    b.insert(b.end(), packed.begin(), packed.end());
    Record(0x06, b, &file_);
  }
  std::string Save(const std::string& name, std::size_t cut = 0) {
    Bytes out = file_;
    Record(0x0F, {0, 0, 0, 0}, &out);  // data end
    Bytes footer(20, 0);
    Record(0x02, footer, &out);
    const Bytes magic{0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
    out.insert(out.end(), magic.begin(), magic.end());
    out.resize(out.size() - cut);
    const std::string path = (aavio::testing::ScratchDir() / name).string();
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
    return path;
  }

 private:
  Bytes file_;
};

std::vector<events::Event> ReadAll(const std::string& path, const std::string& topic = "") {
  auto stream = Ros2BagEventStream::Open(path, topic, {});
  EXPECT_TRUE(stream.ok()) << stream.status().message();
  if (!stream.ok()) return {};
  std::vector<events::Event> out;
  EXPECT_TRUE((*stream)->ReadUntil(std::numeric_limits<TimeNs>::max() / 2, &out).ok());
  EXPECT_TRUE((*stream)->AtEnd());
  EXPECT_EQ((*stream)->info().count, static_cast<std::int64_t>(out.size()));
  EXPECT_EQ((*stream)->info().width, 640);
  return out;
}

TEST(Ros2Bag, Evt3PacketsKeepTheDecoderStateAcrossMessages) {
  std::vector<unsigned char> a, b;
  Put16(&a, 0x8000 | 0xFFF);  // TIME_HIGH just before the 24-bit wrap
  Put16(&a, 0x6000 | 0xFFE);
  Put16(&a, 0x0000 | 12);  // y
  Put16(&a, 0x2000 | (1 << 11) | 5);
  Put16(&b, 0x8000);  // wrapped, in the next packet; y carries over
  Put16(&b, 0x6000 | 3);
  Put16(&b, 0x2000 | 6);
  const std::string bag =
      WriteBag("evt3.db3", {{"/event_camera/events", kPacket}, {"/imu", "sensor_msgs/msg/Imu"}},
               {{1, 100, EventPacket("evt3", 0, a)},
                {1, 200, EventPacket("evt3", 0, b)},
                {2, 150, {0, 1, 0, 0}}});
  const std::vector<events::Event> e = ReadAll(bag);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0], (events::Event{((1ll << 24) - 2) * kNsPerUs, 5, 12, 1}));
  EXPECT_EQ(e[1], (events::Event{((1ll << 24) + 3) * kNsPerUs, 6, 12, 0}));
  auto topics = ListRos2EventTopics(bag);
  ASSERT_TRUE(topics.ok());
  ASSERT_EQ(topics->size(), 1u);
  EXPECT_EQ(topics->front().encoding, "evt3");
  EXPECT_EQ(topics->front().messages, 2);
}

TEST(Ros2Bag, LibcaerPacketsAddTheTimeBaseAndTheWrap) {
  std::vector<unsigned char> p;
  auto event = [&](unsigned x, unsigned y, unsigned pol, std::int32_t us) {
    Put32(&p, (x << 17) | (y << 2) | (pol << 1) | 1);
    Put32(&p, static_cast<std::uint32_t>(us));
  };
  event(639, 479, 1, 2147483000);
  event(3, 4, 0, 100);  // the 31-bit µs counter wrapped inside the packet
  const std::uint64_t base = 1'702'309'000'000'000'000ull;
  const std::string bag =
      WriteBag("caer.db3", {{"/cam/events", kPacket}}, {{1, 1, EventPacket("libcaer", base, p)}});
  const std::vector<events::Event> e = ReadAll(bag, "/cam/events");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0], (events::Event{static_cast<TimeNs>(base) + 2147483000ll * 1000, 639, 479, 1}));
  EXPECT_EQ(e[1], (events::Event{static_cast<TimeNs>(base) + ((1ll << 31) + 100) * 1000, 3, 4, 0}));
}

TEST(Ros2Bag, McapBagsOfLibcaerCmpPacketsInChunksOrAlone) {
  // libcaer_cmp: time high/low (µs since time_base, reset in each packet), x, then single
  // events (ADDR_Y) and vectors of 8 rows (VECT_BASE_Y, VECT_8).
  std::vector<unsigned char> a, b;
  Put16(&a, 0x0000 | 1);                // TIME_HIGH: 1 << 12 µs
  Put16(&a, 0x1000 | 5);                // TIME_LOW
  Put16(&a, 0x2000 | 300);              // x
  Put16(&a, 0x3000 | (1 << 11) | 200);  // an ON event at (300, 200)
  Put16(&a, 0x4000 | 16);               // a vector of OFF events from y = 16
  Put16(&a, 0x5000 | 0x81);             // rows 16 and 23
  Put16(&a, 0x5000 | 0x01);             // the base moved 8 down: row 24
  Put16(&b, 0x1000 | 7);                // a new packet: the high time is 0 again
  Put16(&b, 0x2000 | 1);
  Put16(&b, 0x3000 | 2);
  const std::uint64_t base = 1'744'227'144'732'712'000ull;
  McapWriter w;
  w.Append(McapWriter::Schema(1, kPacket));
  w.Append(McapWriter::Schema(2, "sensor_msgs/msg/Imu"));
  w.Append(McapWriter::Channel(3, 2, "/imu"));
  std::vector<unsigned char> chunk = McapWriter::Channel(1, 1, "/event_camera/events");
  for (const auto& m : {McapWriter::Message(1, 10, EventPacket("libcaer_cmp", base, a)),
                        McapWriter::Message(3, 11, {0, 1, 0, 0})})
    chunk.insert(chunk.end(), m.begin(), m.end());
  w.Chunk(chunk, "lz4");
  w.Chunk(McapWriter::Message(1, 20, EventPacket("libcaer_cmp", base + 10000000, b)), "zstd");
  w.Append(McapWriter::Message(1, 30, EventPacket("libcaer_cmp", base + 20000000, b)));
  const std::string bag = w.Save("caer_cmp.mcap");
  const std::vector<events::Event> e = ReadAll(bag);
  ASSERT_EQ(e.size(), 6u);
  const TimeNs t0 = static_cast<TimeNs>(base) + ((1 << 12) + 5) * 1000;
  EXPECT_EQ(e[0], (events::Event{t0, 300, 200, 1}));
  EXPECT_EQ(e[1], (events::Event{t0, 300, 16, 0}));
  EXPECT_EQ(e[2], (events::Event{t0, 300, 23, 0}));
  EXPECT_EQ(e[3], (events::Event{t0, 300, 24, 0}));
  EXPECT_EQ(e[4], (events::Event{static_cast<TimeNs>(base) + 10000000 + 7000, 1, 2, 0}));
  EXPECT_EQ(e[5], (events::Event{static_cast<TimeNs>(base) + 20000000 + 7000, 1, 2, 0}));
  auto topics = ListRos2EventTopics(bag);
  ASSERT_TRUE(topics.ok()) << topics.status().message();
  ASSERT_EQ(topics->size(), 1u);
  EXPECT_EQ(topics->front().encoding, "libcaer_cmp");
  EXPECT_EQ(topics->front().messages, 3);

  // Cut short, or a chunk of an unknown compression: errors naming the file and the byte.
  auto cut = Ros2BagEventStream::Open(w.Save("cut.mcap", 60), "", {});
  ASSERT_FALSE(cut.ok());
  EXPECT_NE(cut.status().message().find("cut.mcap, byte "), std::string::npos)
      << cut.status().message();
  McapWriter brotli;
  brotli.Chunk(McapWriter::Schema(1, kPacket), "brotli");
  auto c = Ros2BagEventStream::Open(brotli.Save("brotli.mcap"), "", {});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("chunk compression 'brotli' is not read"), std::string::npos)
      << c.status().message();

  // An empty uncompressed chunk holds nothing (it once copied from a null pointer: found by
  // fuzzing under UBSan).
  McapWriter empty;
  empty.Append(McapWriter::Schema(1, kPacket));
  empty.Append(McapWriter::Channel(1, 1, "/event_camera/events"));
  empty.Chunk({}, "");
  empty.Append(McapWriter::Message(1, 30, EventPacket("libcaer_cmp", base, b)));
  EXPECT_EQ(ReadAll(empty.Save("empty_chunk.mcap")).size(), 1u);
}

TEST(Ros2Bag, BadBagsAreClearErrors) {
  const std::string two = WriteBag("two.db3", {{"/a", kPacket}, {"/b", kPacket}}, {});
  auto a = Ros2BagEventStream::Open(two, "", {});
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("several event topics (/a, /b): name one"), std::string::npos)
      << a.status().message();
  auto b = Ros2BagEventStream::Open(two, "/c", {});
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("no EventPacket topic '/c'; its event topics: /a, /b"),
            std::string::npos);

  const std::string mono =
      WriteBag("mono.db3", {{"/a", kPacket}}, {{1, 1, EventPacket("mono", 0, {1, 2})}});
  auto c = Ros2BagEventStream::Open(mono, "", {});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("event encoding 'mono' is not read"), std::string::npos);

  std::vector<unsigned char> cut = EventPacket("evt3", 0, {0, 0x80, 0, 0x60});
  cut.resize(cut.size() - 3);
  const std::string truncated = WriteBag("cut.db3", {{"/a", kPacket}}, {{1, 1, cut}});
  auto d = Ros2BagEventStream::Open(truncated, "", {});
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.status().message().find("message 1 of /a: the EventPacket is truncated"),
            std::string::npos)
      << d.status().message();

  const std::string mcap = (aavio::testing::ScratchDir() / "x.mcap").string();
  std::ofstream(mcap) << "MCAP but not quite";
  auto e = Ros2BagEventStream::Open(mcap, "", {});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("x.mcap: not an MCAP file"), std::string::npos)
      << e.status().message();

  // A topic whose name is NULL (a corrupt bag's metadata): an error, not a crash.
  const std::string unnamed = (aavio::testing::ScratchDir() / "unnamed.db3").string();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(unnamed.c_str(), &db), SQLITE_OK);
  const std::string sql =
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, "
      "data BLOB);"
      "INSERT INTO topics VALUES(7, NULL, '" +
      std::string(kPacket) + "');";
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  for (const Status& status : {ListRos2EventTopics(unnamed).status(),
                               Ros2BagEventStream::Open(unnamed, "", {}).status()}) {
    ASSERT_FALSE(status.ok());
    EXPECT_NE(
        status.message().find("unnamed.db3: the topics table's event topic of id 7 has no name"),
        std::string::npos)
        << status.message();
  }

  const std::string text = (aavio::testing::ScratchDir() / "notabag.db3").string();
  std::ofstream(text) << "hello";
  auto f = Ros2BagEventStream::Open(text, "", {});
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.status().message().find("notabag.db3"), std::string::npos);
}

}  // namespace
}  // namespace aavio::io
