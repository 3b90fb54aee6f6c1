#include "aavio/io/formats/aedat4/aedat4.hpp"

#include <gtest/gtest.h>
#include <lz4frame.h>
#include <zstd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

#include "aavio/io/sequence.hpp"
#include "tests/little_endian.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

/// Writes AEDAT 4.0 files as DV's recorder lays them out: hand-built flatbuffers, each packet
/// compressed with the library the recorder uses.
class Aedat4Writer {
 public:
  enum Compression { kNone = 0, kLz4 = 1, kZstd = 3 };
  struct Ev {
    std::int64_t t_us;
    std::int16_t x, y;
    bool on;
  };
  struct Imu {
    std::int64_t t_us;
    float accel_g[3], gyro_deg_s[3];
  };

  Aedat4Writer(Compression compression, std::string xml_streams)
      : compression_(compression), xml_(std::move(xml_streams)) {}

  void Events(int stream, const std::vector<Ev>& events) {
    std::string b;
    Header(&b, "EVTS");
    b.resize(16);
    Put<std::int32_t>(&b, 8);   // table at 16, vtable at 8
    Put<std::uint32_t>(&b, 4);  // the vector at 24
    Put<std::uint32_t>(&b, static_cast<std::uint32_t>(events.size()));
    for (const Ev& e : events) {
      Put(&b, e.t_us);
      Put(&b, e.x);
      Put(&b, e.y);
      Put<std::uint8_t>(&b, e.on ? 1 : 0);
      b.append(3, '\0');
    }
    Packet(stream, b);
  }

  void ImuSamples(int stream, const std::vector<Imu>& samples) {
    std::string b;
    Header(&b, "IMUS");
    b.resize(16);
    Put<std::int32_t>(&b, 8);
    Put<std::uint32_t>(&b, 4);
    Put<std::uint32_t>(&b, static_cast<std::uint32_t>(samples.size()));
    const std::size_t offsets = b.size();
    b.resize(offsets + 4 * samples.size());
    // One vtable for every IMU table: timestamp, temperature, accelerometer xyz, gyroscope xyz.
    const std::size_t vtable = b.size();
    for (std::uint16_t v : {20, 40, 4, 12, 16, 20, 24, 28, 32, 36})
      Put(&b, v);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const std::size_t table = b.size();
      const std::uint32_t rel = static_cast<std::uint32_t>(table - (offsets + 4 * i));
      std::memcpy(&b[offsets + 4 * i], &rel, 4);
      Put<std::int32_t>(&b, static_cast<std::int32_t>(table - vtable));
      Put(&b, samples[i].t_us);
      Put(&b, 38.0f);
      for (float a : samples[i].accel_g)
        Put(&b, a);
      for (float g : samples[i].gyro_deg_s)
        Put(&b, g);
    }
    Packet(stream, b);
  }

  /// A packet of another type (a frame), never decoded.
  void Other(int stream, std::size_t bytes) { Packet(stream, std::string(bytes, '\x5a')); }

  std::string Save(const std::string& name, std::size_t cut = 0) const {
    // IOHeader: compression, data table position (-1: none), the XML description.
    std::string h;
    Header(&h, "IOHE");
    h.resize(8);
    for (std::uint16_t v : {10, 20, 4, 8, 16})
      Put(&h, v);
    h.resize(20);
    Put<std::int32_t>(&h, 12);
    Put<std::int32_t>(&h, compression_);
    Put<std::int64_t>(&h, -1);
    Put<std::uint32_t>(&h, 4);
    const std::string xml =
        "<dv version=\"2.0\"><node name=\"outInfo\" path=\"/mainloop/Recorder/outInfo/\">" + xml_ +
        "</node></dv>";
    Put<std::uint32_t>(&h, static_cast<std::uint32_t>(xml.size()));
    h += xml;
    h.push_back('\0');
    std::string file = "#!AER-DAT4.0\r\n";
    Put<std::int32_t>(&file, static_cast<std::int32_t>(h.size()));
    file += h + packets_;
    if (cut > 0) file.resize(file.size() - cut);
    const std::string path = (aavio::testing::ScratchDir() / name).string();
    std::ofstream(path, std::ios::binary) << file;
    return path;
  }

  static std::string StreamXml(int id, const std::string& type, const std::string& module,
                               int width = 0, int height = 0) {
    std::string s = "<node name=\"" + std::to_string(id) + "\" path=\"/mainloop/Recorder/outInfo/" +
                    std::to_string(id) + "/\"><attr key=\"originalModuleName\" type=\"string\">" +
                    module + "</attr><attr key=\"typeIdentifier\" type=\"string\">" + type +
                    "</attr>";
    if (width > 0) {
      s += "<node name=\"info\" path=\"/mainloop/Recorder/outInfo/" + std::to_string(id) +
           "/info/\"><attr key=\"sizeX\" type=\"int\">" + std::to_string(width) +
           "</attr><attr key=\"sizeY\" type=\"int\">" + std::to_string(height) + "</attr></node>";
    }
    return s + "</node>";
  }

 private:
  template <typename T>
  static void Put(std::string* b, T v) {
    testing::AppendLittleEndian(b, v);
  }
  static void Header(std::string* b, const char* ident) {
    b->clear();
    Put<std::uint32_t>(b, 16);  // root table at 16 (IOHeader: 20, patched by the caller)
    b->append(ident, 4);
    if (std::string(ident) == "IOHE") std::memcpy(b->data(), "\x14\0\0\0", 4);
    // The packet tables' vtable at 8: one field (the elements vector) at +4.
    for (std::uint16_t v : {6, 8, 4})
      Put(b, v);
  }
  void Packet(int stream, const std::string& flatbuffer) {
    std::string data;
    Put<std::uint32_t>(&data, static_cast<std::uint32_t>(flatbuffer.size()));
    data += flatbuffer;
    std::string out;
    if (compression_ == kLz4) {
      out.resize(LZ4F_compressFrameBound(data.size(), nullptr));
      out.resize(LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), nullptr));
    } else if (compression_ == kZstd) {
      out.resize(ZSTD_compressBound(data.size()));
      out.resize(ZSTD_compress(out.data(), out.size(), data.data(), data.size(), 3));
    } else {
      out = data;
    }
    Put<std::int32_t>(&packets_, stream);
    Put<std::int32_t>(&packets_, static_cast<std::int32_t>(out.size()));
    packets_ += out;
  }

  Compression compression_;
  std::string xml_;
  std::string packets_;
};

template <typename T>
std::vector<T> ReadAll(Stream<T>& stream) {
  std::vector<T> out;
  EXPECT_TRUE(stream.ReadUntil(std::numeric_limits<TimeNs>::max() / 2, &out).ok());
  EXPECT_TRUE(stream.AtEnd());
  return out;
}

const std::string kDavis = Aedat4Writer::StreamXml(0, "EVTS", "capture", 346, 260) +
                           Aedat4Writer::StreamXml(1, "FRME", "capture") +
                           Aedat4Writer::StreamXml(2, "IMUS", "capture");

TEST(Aedat4, EventsAndImuOfAnLz4RecordingWithFramesSkipped) {
  Aedat4Writer w(Aedat4Writer::kLz4, kDavis);
  w.Events(0, {{1589163005536052, 10, 20, true}, {1589163005536060, 345, 259, false}});
  w.Other(1, 300);
  w.ImuSamples(2, {{1589163005536000, {0.0f, -1.0f, 0.5f}, {90.0f, 0.0f, -180.0f}},
                   {1589163005537000, {0.1f, -0.9f, 0.4f}, {1.0f, 2.0f, 3.0f}}});
  w.Events(0, {{1589163005536070, 0, 0, true}, {1589163005536065, 5, 6, false}});  // 5 µs back
  const std::string path = w.Save("davis.aedat4");

  auto events = OpenAedat4EventStream(path, "", {});
  ASSERT_TRUE(events.ok()) << events.status().message();
  const StreamInfo& info = (*events)->info();
  EXPECT_EQ(info.count, 4);
  EXPECT_EQ(info.width, 346);
  EXPECT_EQ(info.height, 260);
  EXPECT_EQ(info.t_first_ns, 1589163005536052000);
  EXPECT_EQ(info.t_last_ns, 1589163005536070000);
  const std::vector<events::Event> e = ReadAll(**events);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0], (events::Event{1589163005536052000, 10, 20, 1}));
  EXPECT_EQ(e[1], (events::Event{1589163005536060000, 345, 259, 0}));
  EXPECT_EQ(e[2], (events::Event{1589163005536065000, 5, 6, 0}));  // put back in time order
  EXPECT_EQ(e[3], (events::Event{1589163005536070000, 0, 0, 1}));

  auto imu = OpenAedat4ImuStream(path, "", {});
  ASSERT_TRUE(imu.ok()) << imu.status().message();
  const std::vector<imu::ImuSample> s = ReadAll(**imu);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].t_ns, 1589163005536000000);
  EXPECT_NEAR(s[0].accel_m_s2.y(), -9.80665, 1e-5);  // g → m/s²
  EXPECT_NEAR(s[0].accel_m_s2.z(), 0.5 * 9.80665, 1e-5);
  EXPECT_NEAR(s[0].gyro_rad_s.x(), std::numbers::pi / 2, 1e-6);  // °/s → rad/s
  EXPECT_NEAR(s[0].gyro_rad_s.z(), -std::numbers::pi, 1e-6);
  EXPECT_NEAR(s[1].gyro_rad_s.y(), 2.0 * std::numbers::pi / 180.0, 1e-7);
}

TEST(Aedat4, ZstandardAndUncompressedFilesAndSeek) {
  for (auto c : {Aedat4Writer::kZstd, Aedat4Writer::kNone}) {
    Aedat4Writer w(c, kDavis);
    std::vector<Aedat4Writer::Ev> first, second;
    for (int i = 0; i < 100; ++i)
      first.push_back({1000 + i, static_cast<std::int16_t>(i), 7, i % 2 == 0});
    for (int i = 0; i < 100; ++i)
      second.push_back({2000 + i, 3, static_cast<std::int16_t>(i), false});
    w.Events(0, first);
    w.Events(0, second);
    auto s = OpenAedat4EventStream(w.Save("c" + std::to_string(c) + ".aedat4"), "0", {});
    ASSERT_TRUE(s.ok()) << s.status().message();
    EXPECT_EQ((*s)->info().count, 200);
    std::vector<events::Event> part;
    ASSERT_TRUE((*s)->ReadUntil(1050 * 1000, &part).ok());
    EXPECT_EQ(part.size(), 50u);
    ASSERT_TRUE((*s)->Seek(2090 * 1000).ok());
    const std::vector<events::Event> rest = ReadAll(**s);
    ASSERT_EQ(rest.size(), 10u);
    EXPECT_EQ(rest.front().t_ns, 2090 * 1000);
    // Back into the first packet, and before the start.
    ASSERT_TRUE((*s)->Seek(1050 * 1000).ok());
    EXPECT_EQ(ReadAll(**s).size(), 150u);
    ASSERT_TRUE((*s)->Seek(0).ok());
    EXPECT_EQ(ReadAll(**s).size(), 200u);
  }
}

TEST(Aedat4, ASequenceOfTwoCamerasAndTheirImu) {
  Aedat4Writer left(Aedat4Writer::kLz4, kDavis), right(Aedat4Writer::kLz4, kDavis);
  left.Events(0, {{1000, 1, 1, true}, {3000, 2, 2, true}});
  left.ImuSamples(2, {{1000, {0, 0, 1}, {0, 0, 0}}, {2000, {0, 0, 1}, {0, 0, 10}}});
  right.Events(0, {{1500, 3, 3, false}});
  const std::string lp = left.Save("left.aedat4"), rp = right.Save("right.aedat4");
  const auto folder = aavio::testing::ScratchDir() / "aedat4_sequence";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "sequence.yaml")
      << "name: dv\nevents:\n  left: " << lp << "\n  right: " << rp << "\nimu:\n  path: " << lp
      << "\n";
  auto d = DescribeSequence((folder / "sequence.yaml").string());
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_EQ(d->left.format, SourceFormat::kAedat4);
  EXPECT_TRUE(d->left.topic.empty());
  auto reader = SequenceReader::Open(*d, {});
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  std::size_t left_n = 0, right_n = 0, imu_n = 0;
  SensorPacket packet;
  while (true) {
    Expected<bool> more = (*reader)->Next(&packet);
    ASSERT_TRUE(more.ok()) << more.status().message();
    if (!*more) break;
    left_n += packet.left.size();
    right_n += packet.right.size();
    imu_n += packet.imu.size();
  }
  EXPECT_EQ(left_n, 2u);
  EXPECT_EQ(right_n, 1u);
  EXPECT_EQ(imu_n, 2u);
}

TEST(Aedat4, BadFilesNameTheFileTheByteAndTheFix) {
  auto message = [](const Expected<std::unique_ptr<EventStream>>& s) {
    return s.ok() ? std::string("opened") : s.status().message();
  };
  const std::string plain = (aavio::testing::ScratchDir() / "aedat2.aedat4").string();
  std::ofstream(plain) << "#!AER-DAT2.0\r\n# This is a raw AE data file\r\n";
  EXPECT_NE(message(OpenAedat4EventStream(plain, "", {})).find("not an AEDAT 4.0 file"),
            std::string::npos);

  Aedat4Writer cut(Aedat4Writer::kLz4, kDavis);
  cut.Events(0, {{1000, 1, 1, true}, {2000, 2, 2, false}});
  const std::string m = message(OpenAedat4EventStream(cut.Save("cut.aedat4", 7), "", {}));
  EXPECT_NE(m.find("cut.aedat4, byte "), std::string::npos) << m;
  EXPECT_NE(m.find("claims"), std::string::npos) << m;

  Aedat4Writer outside(Aedat4Writer::kNone, kDavis);
  outside.Events(0, {{1000, 346, 1, true}});
  const std::string o = message(OpenAedat4EventStream(outside.Save("outside.aedat4"), "", {}));
  EXPECT_NE(o.find("outside the 346x260 sensor"), std::string::npos) << o;

  Aedat4Writer corrupt(Aedat4Writer::kLz4, kDavis);
  corrupt.Events(0, {{1000, 1, 1, true}});
  std::string path = corrupt.Save("corrupt.aedat4");
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-6, std::ios::end);
    f.write("\xff\xff\xff\xff", 4);
  }
  const std::string c = message(OpenAedat4EventStream(path, "", {}));
  EXPECT_NE(c.find("corrupt.aedat4, byte "), std::string::npos) << c;

  const std::string two_cameras = Aedat4Writer::StreamXml(0, "EVTS", "left", 346, 260) +
                                  Aedat4Writer::StreamXml(1, "EVTS", "right", 346, 260);
  Aedat4Writer stereo(Aedat4Writer::kLz4, two_cameras);
  stereo.Events(0, {{1000, 1, 1, true}});
  stereo.Events(1, {{1000, 2, 2, true}, {1001, 3, 3, true}});
  const std::string sp = stereo.Save("stereo.aedat4");
  const std::string t = message(OpenAedat4EventStream(sp, "", {}));
  EXPECT_NE(t.find("2 EVTS streams; name one"), std::string::npos) << t;
  auto right = OpenAedat4EventStream(sp, "right", {});
  ASSERT_TRUE(right.ok()) << right.status().message();
  EXPECT_EQ((*right)->info().count, 2);
  EXPECT_NE(message(OpenAedat4EventStream(sp, "middle", {})).find("no EVTS stream named 'middle'"),
            std::string::npos);
  EXPECT_FALSE(OpenAedat4ImuStream(sp, "", {}).ok());
}

}  // namespace
}  // namespace aavio::io
