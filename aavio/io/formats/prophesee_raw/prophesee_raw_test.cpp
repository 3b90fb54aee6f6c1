#include "aavio/io/formats/prophesee_raw/prophesee_raw.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/little_endian.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

/// Little-endian EVT words after a header, written as a Metavision recorder would.
class RawWriter {
 public:
  explicit RawWriter(std::string header) : bytes_(std::move(header)) {}
  void Word16(unsigned w) { testing::AppendLittleEndian(&bytes_, static_cast<std::uint16_t>(w)); }
  void Word32(std::uint32_t w) { testing::AppendLittleEndian(&bytes_, w); }
  // EVT 2.0
  void Evt2TimeHigh(std::uint64_t t_us) {
    Word32(0x80000000u | static_cast<std::uint32_t>((t_us >> 6) & 0x0FFFFFFF));
  }
  void Evt2Cd(std::uint64_t t_us, unsigned x, unsigned y, unsigned p) {
    Word32((p ? 0x10000000u : 0u) | static_cast<std::uint32_t>((t_us & 0x3F) << 22) | (x << 11) |
           y);
  }
  // EVT 3.0
  void Evt3Time(std::uint64_t t_us) {
    Word16(0x8000 | ((t_us >> 12) & 0xFFF));
    Word16(0x6000 | (t_us & 0xFFF));
  }
  void Evt3Y(unsigned y) { Word16(y); }
  void Evt3X(unsigned x, unsigned p) { Word16(0x2000 | (p << 11) | x); }
  void Evt3Base(unsigned x, unsigned p) { Word16(0x3000 | (p << 11) | x); }
  void Evt3Vect12(unsigned mask) { Word16(0x4000 | mask); }
  void Evt3Vect8(unsigned mask) { Word16(0x5000 | mask); }
  std::string Save(const std::string& name) const {
    const std::string path = (aavio::testing::ScratchDir() / name).string();
    std::ofstream(path, std::ios::binary) << bytes_;
    return path;
  }
  std::string bytes_;
};

std::vector<events::Event> ReadAll(const std::string& path, StreamInfo* info = nullptr) {
  auto stream = PropheseeRawEventStream::Open(path, {});
  EXPECT_TRUE(stream.ok()) << stream.status().message();
  if (!stream.ok()) return {};
  if (info) *info = (*stream)->info();
  std::vector<events::Event> out;
  EXPECT_TRUE((*stream)->ReadUntil(std::numeric_limits<TimeNs>::max() / 2, &out).ok());
  EXPECT_TRUE((*stream)->AtEnd());
  return out;
}

TEST(PropheseeRaw, Evt2EventsWithTheirTimeAndGeometryFromThePlugin) {
  RawWriter w("% date 2020-09-14\n% evt 2.0\n% plugin_name hal_plugin_gen3_fx3\n");
  w.Evt2Cd(5, 1, 1, 1);  // before any TIME_HIGH: skipped
  w.Evt2TimeHigh(1'317'888);
  w.Evt2Cd(1'317'888, 10, 20, 1);
  w.Evt2Cd(1'317'890, 639, 479, 0);
  w.Word32(0xA0000000u);  // a trigger: ignored
  w.Evt2TimeHigh(1'317'952);
  w.Evt2Cd(1'317'960, 3, 4, 1);
  StreamInfo info;
  const std::vector<events::Event> e = ReadAll(w.Save("evt2.raw"), &info);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0], (events::Event{1'317'888'000, 10, 20, 1}));
  EXPECT_EQ(e[1], (events::Event{1'317'890'000, 639, 479, 0}));
  EXPECT_EQ(e[2].t_ns, 1'317'960'000);
  EXPECT_EQ(info.width, 640);
  EXPECT_EQ(info.height, 480);
  EXPECT_EQ(info.count, 3);
  EXPECT_EQ(info.t_last_ns, 1'317'960'000);
}

TEST(PropheseeRaw, Evt3VectorsWrapAndSteppedBackTimeLow) {
  RawWriter w("% format EVT3;height=720;width=1280\n% end\n");
  w.Evt3Time((1u << 24) - 10);  // just before the 24-bit wrap
  w.Evt3Y(7);
  w.Evt3X(100, 1);
  w.Evt3Base(200, 0);
  w.Evt3Vect12(0b100000000101);  // x 200, 202, 211
  w.Evt3Vect8(0b10000001);       // x 212, 219
  w.Evt3Time(5);                 // wrapped: 2^24 + 5 µs
  w.Evt3X(1, 1);
  w.Word16(0x6000 | 3);  // TIME_LOW 2 µs back, as Gen4 streams do
  w.Evt3X(2, 0);
  StreamInfo info;
  const std::vector<events::Event> e = ReadAll(w.Save("evt3.raw"), &info);
  ASSERT_EQ(e.size(), 8u);
  const TimeNs t0 = ((1ll << 24) - 10) * kNsPerUs;
  EXPECT_EQ(e[0], (events::Event{t0, 100, 7, 1}));
  const std::vector<int> xs = {200, 202, 211, 212, 219};
  for (std::size_t k = 0; k < xs.size(); ++k) {
    EXPECT_EQ(e[1 + k].x, xs[k]);
    EXPECT_EQ(e[1 + k].polarity, 0);
    EXPECT_EQ(e[1 + k].t_ns, t0);
  }
  EXPECT_EQ(e[6], (events::Event{((1ll << 24) + 3) * kNsPerUs, 2, 7, 0}));  // put in order
  EXPECT_EQ(e[7], (events::Event{((1ll << 24) + 5) * kNsPerUs, 1, 7, 1}));
  EXPECT_EQ(info.width, 1280);
  EXPECT_EQ(info.count, 8);
}

TEST(PropheseeRaw, SeekRestartsAtTheTime) {
  RawWriter w("% evt 3.0\n");
  for (int k = 0; k < 100; ++k) {
    w.Evt3Time(1000u * static_cast<unsigned>(k));
    w.Evt3Y(1);
    w.Evt3X(static_cast<unsigned>(k), 1);
  }
  auto stream = PropheseeRawEventStream::Open(w.Save("seek.raw"), {});
  ASSERT_TRUE(stream.ok());
  std::vector<events::Event> out;
  ASSERT_TRUE((*stream)->ReadUntil(10 * kNsPerMs, &out).ok());
  EXPECT_EQ(out.size(), 10u);
  ASSERT_TRUE((*stream)->Seek(50 * kNsPerMs).ok());
  out.clear();
  ASSERT_TRUE((*stream)->ReadUntil(60 * kNsPerMs, &out).ok());
  ASSERT_EQ(out.size(), 10u);
  EXPECT_EQ(out.front().x, 50);
}

TEST(PropheseeRaw, BadFilesNameTheFileTheByteAndTheCause) {
  RawWriter no_header("");
  no_header.Evt3Time(1);
  auto a = PropheseeRawEventStream::Open(no_header.Save("plain.raw"), {});
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("no '% evt' or '% format' header"), std::string::npos);

  RawWriter evt21("% format EVT21;height=720;width=1280\n");
  auto b = PropheseeRawEventStream::Open(evt21.Save("evt21.raw"), {});
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("EVT 2.1 is not read"), std::string::npos);

  RawWriter corrupt("% evt 3.0\n");
  corrupt.Evt3Time(1);
  corrupt.Word16(0x9123);  // no EVT 3.0 word has type 9
  auto c = PropheseeRawEventStream::Open(corrupt.Save("corrupt.raw"), {});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("word type 0x9 at byte 14"), std::string::npos)
      << c.status().message();

  RawWriter truncated("% evt 2.0\n");
  truncated.Evt2TimeHigh(64);
  truncated.bytes_ += "\x01\x02";  // half a word
  auto d = PropheseeRawEventStream::Open(truncated.Save("truncated.raw"), {});
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.status().message().find("truncated"), std::string::npos);

  RawWriter outside("% evt 3.0\n% geometry 640x480\n");
  outside.Evt3Time(1);
  outside.Evt3Y(500);
  outside.Evt3X(3, 1);
  auto e = PropheseeRawEventStream::Open(outside.Save("outside.raw"), {});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("(3, 500) outside the 640 x 480 sensor"), std::string::npos);

  auto missing = PropheseeRawEventStream::Open("/nonexistent/x.raw", {});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("/nonexistent/x.raw"), std::string::npos);
}

}  // namespace
}  // namespace aavio::io
