#include "aavio/io/ros2_bag.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fstream>

#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

/// Little-endian CDR, aligned like the ROS 2 middleware writes it.
class CdrWriter {
 public:
  CdrWriter() : bytes_{0x00, 0x01, 0x00, 0x00} {}
  void U32(std::uint32_t v) { Fixed(v, 4); }
  void U64(std::uint64_t v) { Fixed(v, 8); }
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
  void Fixed(std::uint64_t v, std::size_t n) {
    while ((bytes_.size() - 4) % n != 0)
      bytes_.push_back(0);
    for (std::size_t k = 0; k < n; ++k)
      bytes_.push_back(static_cast<unsigned char>(v >> (8 * k)));
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
  b->push_back(static_cast<unsigned char>(w & 0xFF));
  b->push_back(static_cast<unsigned char>(w >> 8));
}
void Put32(std::vector<unsigned char>* b, std::uint32_t w) {
  Put16(b, w & 0xFFFF);
  Put16(b, w >> 16);
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
  std::ofstream(mcap) << "\x89MCAP0\r\n";
  auto e = Ros2BagEventStream::Open(mcap, "", {});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("MCAP storage is not read yet"), std::string::npos);

  const std::string text = (aavio::testing::ScratchDir() / "notabag.db3").string();
  std::ofstream(text) << "hello";
  auto f = Ros2BagEventStream::Open(text, "", {});
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.status().message().find("notabag.db3"), std::string::npos);
}

}  // namespace
}  // namespace aavio::io
