// DSEC-layout HDF5: read files written by h5py + hdf5plugin, and our writer's files read back by
// h5py (tests/fixtures/check_dsec_h5.py) and by our reader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <mutex>
#include <thread>

#include "aavio/io/formats/dsec_h5/dsec_h5_reader.hpp"
#include "aavio/io/formats/dsec_h5/dsec_h5_writer.hpp"
#include "aavio/io/formats/dsec_h5/hdf5_util.hpp"
#include "tests/event_fixtures.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

using testing::ExpectedEvents;
using testing::Fixture;

std::unique_ptr<DsecH5EventStream> OpenOk(const std::string& name, StreamOptions options = {}) {
  auto stream = DsecH5EventStream::Open(Fixture(name + ".h5"), options);
  EXPECT_TRUE(stream.ok()) << stream.status().message();
  return stream.ok() ? std::move(*stream) : nullptr;
}

class DsecH5Variants : public ::testing::TestWithParam<const char*> {};

TEST_P(DsecH5Variants, ReadsExactlyWhatH5pyWrote) {
  const std::string name = GetParam();
  const std::vector<events::Event> expected = ExpectedEvents(name);
  auto stream = OpenOk(name, {.max_reorder_ns = kNsPerMs,
                              .width = 640,
                              .height = 480,
                              .block_events = 7777});  // blocks across chunk boundaries
  ASSERT_TRUE(stream);
  EXPECT_EQ(stream->info().count, static_cast<std::int64_t>(expected.size()));
  EXPECT_EQ(stream->info().t_first_ns, expected.front().t_ns);
  EXPECT_EQ(stream->info().t_last_ns, expected.back().t_ns);
  const std::vector<events::Event> got = testing::ReadAllOf(*stream, kNsPerMs);
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_TRUE(got == expected);
}

// docs/io.md: blosc/zstd/bit-shuffle with a large t_offset; t_offset of shape (1,); TUM-VIE
// style (no t_offset, int64 t, int8 p); uncompressed; no ms_to_idx; a small disorder (reordered).
INSTANTIATE_TEST_SUITE_P(Fixtures, DsecH5Variants,
                         ::testing::Values("dsec_blosc", "offset_shape1", "tumvie", "uncompressed",
                                           "no_ms_to_idx", "small_disorder"));

TEST(DsecH5, MsToIdxMatchesTheDefinition) {
  auto stream = OpenOk("dsec_blosc");
  ASSERT_TRUE(stream);
  const std::vector<events::Event> expected = ExpectedEvents("dsec_blosc");
  const auto& idx = stream->ms_to_idx();
  ASSERT_FALSE(idx.empty());
  const std::int64_t offset = stream->t_offset_us();
  EXPECT_EQ(offset, 36470123457LL);
  for (std::size_t ms = 0; ms < idx.size(); ms += 17) {
    // ms_to_idx[ms] = first event with t >= 1000 ms (t relative to t_offset, in µs).
    const auto first = std::lower_bound(
        expected.begin(), expected.end(), ms, [&](const events::Event& e, std::size_t m) {
          return e.t_ns / 1000 - offset < static_cast<std::int64_t>(m) * 1000;
        });
    EXPECT_EQ(idx[ms], static_cast<std::uint64_t>(first - expected.begin())) << ms;
  }
}

TEST(DsecH5, SeekStartsAtTheFirstEventAtOrAfterTheTarget) {
  const std::vector<events::Event> expected = ExpectedEvents("dsec_blosc");
  for (const char* name : {"dsec_blosc", "no_ms_to_idx"}) {
    auto stream = OpenOk(name);
    ASSERT_TRUE(stream);
    for (std::size_t k : {0ul, 1ul, 12345ul, 100000ul, 199999ul}) {
      const TimeNs target = expected[k].t_ns;
      ASSERT_TRUE(stream->Seek(target).ok());
      std::vector<events::Event> out;
      ASSERT_TRUE(stream->ReadUntil(target + 2 * kNsPerMs, &out).ok());
      const auto first =
          std::lower_bound(expected.begin(), expected.end(), target,
                           [](const events::Event& e, TimeNs t) { return e.t_ns < t; });
      const auto last =
          std::lower_bound(expected.begin(), expected.end(), target + 2 * kNsPerMs,
                           [](const events::Event& e, TimeNs t) { return e.t_ns < t; });
      ASSERT_EQ(out.size(), static_cast<std::size_t>(last - first)) << name << " k=" << k;
      EXPECT_TRUE(std::equal(out.begin(), out.end(), first)) << name;
    }
  }
}

TEST(DsecH5, EmptyFileIsAnEmptyStream) {
  auto stream = OpenOk("empty");
  ASSERT_TRUE(stream);
  EXPECT_EQ(stream->info().count, 0);
  EXPECT_TRUE(stream->AtEnd());
  std::vector<events::Event> out;
  EXPECT_TRUE(stream->ReadUntil(kNsPerS, &out).ok());
  EXPECT_TRUE(out.empty());
}

TEST(DsecH5, BadFilesGiveClearErrors) {
  struct Case {
    const char* file;
    const char* expected;
  };
  const std::vector<Case> open_errors = {
      {"wrong_dtype.h5", "/events/x must hold integers"},
      {"missing_t.h5", "missing /events/t"},
      {"length_mismatch.h5", "must have the same length"},
      {"truncated.h5", "truncated file"},
      {"not_hdf5.h5", "not a readable HDF5 file"},
      {"does_not_exist.h5", "no such file"},
      {"t_overflow.h5", "/events/t + /t_offset is beyond what nanoseconds hold"},
  };
  for (const Case& c : open_errors) {
    auto stream = DsecH5EventStream::Open(Fixture(c.file), {});
    ASSERT_FALSE(stream.ok()) << c.file;
    EXPECT_NE(stream.status().message().find(c.expected), std::string::npos)
        << c.file << ": " << stream.status().message();
    EXPECT_NE(stream.status().message().find(c.file), std::string::npos) << "names the file";
  }
  const std::vector<Case> read_errors = {
      {"backwards", "event 150000: timestamp 36470.280811000 s goes back 30.000 ms"},
      {"outside", "event 5000 at (700,"},
      {"negative_x", "event 7000 has x = -3, y = "},
      {"polarity_7", "event 9000 has x = "},
      {"corrupt", "the file is truncated or corrupt (HDF5: Blosc decompression error"},
      // Event 1 is the largest stamp nanoseconds hold (read), event 2 one µs more.
      {"t_overflow_inside", "event 2 at t = 4719772409484280 µs (+ t_offset 4503599627370496)"},
  };
  for (const Case& c : read_errors) {
    auto stream = OpenOk(c.file, {.width = 640, .height = 480});
    ASSERT_TRUE(stream);
    std::vector<events::Event> out;
    Status s;
    while (s.ok() && !stream->AtEnd()) {
      s = stream->ReadUntil(stream->info().t_last_ns + 1, &out);
    }
    ASSERT_FALSE(s.ok()) << c.file;
    EXPECT_NE(s.message().find(c.expected), std::string::npos) << s.message();
  }
}

// The blosc plugin is found through HDF5's plugin path, read once per process: a child process
// with the path pointing nowhere sees the file as a user without the Debian package would.
TEST(DsecH5, MissingBloscPluginNamesTheDebianPackage) {
  const std::string command =
      "HDF5_PLUGIN_PATH=/nonexistent " AAVIO_BINARY " info " + Fixture("dsec_blosc.h5") + " 2>&1";
  std::FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (std::fgets(buffer, sizeof(buffer), pipe))
    output += buffer;
  const int status = pclose(pipe);
  EXPECT_NE(status, 0);
  EXPECT_NE(output.find("hdf5-filter-plugin-blosc-serial"), std::string::npos) << output;
}

TEST(DsecH5, AbsurdElementTypesAreACorruptFileNotAnOverflow) {
  // Found by fuzzing (fuzz/corpus/dsec_h5 keeps it): /events/x declares 33554434-byte integers,
  // which HDF5 1.10 would convert by reading past its buffers.
  auto s = DsecH5EventStream::Open(
      AAVIO_SOURCE_DIR "/fuzz/corpus/dsec_h5/regression_huge_element.h5", {});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find(
                "/events/x holds elements of 33554434 bytes, not numbers of 1 to 8 bytes"),
            std::string::npos)
      << s.status().message();
}

TEST(DsecH5, AFileThatCrashesHdf5ItselfIsAnErrorNotACrash) {
  // Found by fuzzing: a corrupt local heap makes HDF5 1.10.8 dereference a failed allocation
  // inside H5Gopen. The open is tried in a child process first; its crash is reported.
  const std::string path = AAVIO_SOURCE_DIR "/fuzz/corpus/dsec_h5/regression_corrupt_local_heap.h5";
  auto s = DsecH5EventStream::Open(path, {});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find(path + ": the HDF5 library crashed ("), std::string::npos)
      << s.status().message();
  EXPECT_NE(s.status().message().find("the file is corrupt"), std::string::npos);
  EXPECT_FALSE(ReadDsecRectifyMap(path).ok());
}

TEST(DsecH5, AChildThatHangsIsStoppedAndReported) {
  const Status status = h5::SurvivesInChild(
      "x.h5",
      [] {
        for (;;)
          pause();
      },
      0.2);
  EXPECT_NE(status.message().find("x.h5: the HDF5 library did not finish reading"),
            std::string::npos)
      << status.message();
  EXPECT_TRUE(h5::SurvivesInChild("x.h5", [] {}).ok());
  EXPECT_NE(h5::SurvivesInChild("x.h5", [] { std::abort(); }).message().find("crashed (signal 6"),
            std::string::npos);
}

TEST(DsecH5, AChildForkedWhileAnotherThreadHoldsALockIsForkedAgain) {
  // fork copies the other thread's locked mutex but not the thread that would unlock it: a child
  // that needs it waits forever. That is not a corrupt file; the probe forks again.
  std::mutex mutex;
  std::promise<void> locked;
  std::thread holder([&] {
    const std::lock_guard<std::mutex> hold(mutex);
    locked.set_value();
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  });
  locked.get_future().wait();
  const Status status = h5::SurvivesInChild(
      "x.h5", [&] { const std::lock_guard<std::mutex> g(mutex); }, 30.0);
  holder.join();
  EXPECT_TRUE(status.ok()) << status.message();
}

TEST(DsecH5, AChildThatStallsEveryTimeOrSpinsIsAnErrorSayingWhich) {
  std::mutex mutex;
  std::promise<void> locked, release;
  std::thread holder([&] {
    const std::lock_guard<std::mutex> hold(mutex);
    locked.set_value();
    release.get_future().wait();
  });
  locked.get_future().wait();
  const Status stalled = h5::SurvivesInChild(
      "x.h5", [&] { const std::lock_guard<std::mutex> g(mutex); }, 30.0);
  // With another thread running, a child busy in HDF5 is not taken for a stalled one.
  const Status spins = h5::SurvivesInChild(
      "x.h5",
      [] {
        std::atomic<unsigned> turns{0};
        for (;;)
          turns.fetch_add(1, std::memory_order_relaxed);
      },
      2.5);
  release.set_value();
  holder.join();
  EXPECT_NE(
      stalled.message().find("x.h5: reading the file's structure in a child process stalled 5 "
                             "times (another thread of this process holds a lock"),
      std::string::npos)
      << stalled.message();
  EXPECT_NE(spins.message().find("x.h5: the HDF5 library did not finish reading"),
            std::string::npos)
      << spins.message();
}

TEST(DsecH5, AnIndexLongerThanTheRecordingIsIgnoredNotAllocated) {
  // Found by fuzzing: /ms_to_idx declaring 2^50 entries was allocated before it was checked.
  auto s = DsecH5EventStream::Open(Fixture("huge_ms_to_idx.h5"), {});
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_NE((*s)->info().description.find("ms_to_idx longer than the recording, ignored"),
            std::string::npos)
      << (*s)->info().description;
  EXPECT_EQ(testing::ReadAllOf(**s, kNsPerMs).size(),
            testing::ExpectedEvents("huge_ms_to_idx").size());
}

TEST(DsecH5, ReadsRectifyMap) {
  Expected<cv::Mat> map = ReadDsecRectifyMap(Fixture("rectify_map.h5"));
  ASSERT_TRUE(map.ok()) << map.status().message();
  EXPECT_EQ(map->cols, 640);
  EXPECT_EQ(map->rows, 480);
  EXPECT_EQ(map->type(), CV_32FC2);
  const cv::Vec2f v = map->at<cv::Vec2f>(100, 200);  // row 100, column 200
  EXPECT_FLOAT_EQ(v[0], 200.25f);
  EXPECT_FLOAT_EQ(v[1], 99.75f);
  EXPECT_FALSE(ReadDsecRectifyMap(Fixture("dsec_blosc.h5")).ok());
}

TEST(DsecH5Writer, RoundTripsAndH5pyAgrees) {
  const std::vector<events::Event> expected = ExpectedEvents("dsec_blosc");
  const auto dir = testing::ScratchDir();
  const std::string path = (dir / "events.h5").string();
  {
    auto writer = DsecH5EventWriter::Create(path, {.chunk_events = 4096});
    ASSERT_TRUE(writer.ok()) << writer.status().message();
    // Uneven pieces, as a simulator would produce them.
    std::size_t at = 0;
    for (std::size_t piece = 1; at < expected.size(); piece = piece * 3 % 10007 + 1) {
      const std::size_t n = std::min(piece, expected.size() - at);
      ASSERT_TRUE((*writer)->Write(std::span(expected).subspan(at, n)).ok());
      at += n;
    }
    ASSERT_TRUE((*writer)->Close().ok());
  }
  auto stream = DsecH5EventStream::Open(path, {});
  ASSERT_TRUE(stream.ok()) << stream.status().message();
  EXPECT_EQ((*stream)->t_offset_us(), 36470123000LL);  // first event, down to the millisecond
  const std::vector<events::Event> got = testing::ReadAllOf(**stream, 3 * kNsPerMs);
  EXPECT_TRUE(got == expected);
  // h5py (independent reader) checks the layout, blosc options, ms_to_idx and the values.
  const std::string command = "/usr/bin/python3 " AAVIO_SOURCE_DIR
                              "/tests/fixtures/check_dsec_h5.py " +
                              path + " " + Fixture("dsec_blosc.events.bin");
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(DsecH5Writer, RefusesUnorderedEventsAndTooLongFiles) {
  const auto dir = testing::ScratchDir();
  auto writer = DsecH5EventWriter::Create((dir / "a.h5").string());
  ASSERT_TRUE(writer.ok());
  const std::vector<events::Event> backwards = {{2 * kNsPerS, 1, 1, 1}, {kNsPerS, 1, 1, 1}};
  Status s = (*writer)->Write(backwards);
  EXPECT_NE(s.message().find("time order"), std::string::npos);
  auto writer2 = DsecH5EventWriter::Create((dir / "b.h5").string());
  const std::vector<events::Event> long_file = {{0, 1, 1, 1}, {5000 * kNsPerS, 1, 1, 1}};
  s = (*writer2)->Write(long_file);
  EXPECT_NE(s.message().find("71.6 minutes"), std::string::npos) << s.message();
  EXPECT_FALSE(DsecH5EventWriter::Create("/nonexistent/dir/x.h5").ok());
}

}  // namespace
}  // namespace aavio::io
