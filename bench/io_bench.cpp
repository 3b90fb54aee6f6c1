// Decode throughput of the streaming readers on one core, files in the page cache
// (issue: ≥ 30 M events/s from DSEC h5, ≥ 20 M events/s from an lz4 bag).
// The files are written once per run by aavio's writers into $TMPDIR: 10 M events of a
// DSEC-like stream (640x480, ~5 M ev/s, µs timestamps, blosc/zstd/bit-shuffle; lz4 bag in 1 ms
// packets; Prophesee RAW EVT 2.0, encoded here as Metavision writes it).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "aavio/io/formats/dsec_h5/dsec_h5_reader.hpp"
#include "aavio/io/formats/dsec_h5/dsec_h5_writer.hpp"
#include "aavio/io/formats/prophesee_raw/prophesee_raw.hpp"
#include "aavio/io/formats/rosbag/bag_streams.hpp"
#include "aavio/io/formats/rosbag/bag_writer.hpp"

namespace {

using aavio::TimeNs;
using aavio::events::Event;

constexpr std::size_t kEvents = 10'000'000;

std::vector<Event> MakeEvents(std::size_t n) {
  // Events cluster on moving edges in real data; a mix of structured and random positions keeps
  // compression near that of real recordings rather than of pure noise.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> jitter(0, 3), col(0, 639), row(0, 479), gap(0, 400);
  std::vector<Event> events(n);
  TimeNs t = 36470123457LL * 1000;
  for (std::size_t i = 0; i < n; ++i) {
    t += gap(rng);  // mean 200 ns → 5 M ev/s
    const int edge = static_cast<int>((i / 64) % 640);
    const bool on_edge = (i % 4) != 0;
    events[i] = {t, static_cast<std::uint16_t>(on_edge ? (edge + jitter(rng)) % 640 : col(rng)),
                 static_cast<std::uint16_t>(row(rng)), static_cast<std::uint8_t>(i & 1)};
  }
  return events;
}

// EVT 2.0: a TIME_HIGH word (type 8, t[33:6] µs) whenever the upper bits change, then one CD word
// per event (type 0 OFF / 1 ON, t[5:0] in bits 27..22, x in 21..11, y in 10..0), little-endian.
void WriteEvt2(const std::string& path, const std::vector<Event>& events) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return;
  std::fputs("% evt 2.0\n% format EVT2;height=480;width=640\n% end\n", f);
  std::vector<std::uint32_t> words;
  words.reserve(events.size() + events.size() / 16);
  std::int64_t high = -1;
  for (const Event& e : events) {
    const std::int64_t us = e.t_ns / 1000;
    if ((us >> 6) != high) {
      high = us >> 6;
      words.push_back((8u << 28) | static_cast<std::uint32_t>(high & 0x0FFFFFFF));
    }
    words.push_back((static_cast<std::uint32_t>(e.polarity ? 1 : 0) << 28) |
                    (static_cast<std::uint32_t>(us & 63) << 22) |
                    (static_cast<std::uint32_t>(e.x) << 11) | e.y);
  }
  std::fwrite(words.data(), sizeof(std::uint32_t), words.size(), f);
  std::fclose(f);
}

const std::string& Dir() {
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() / "aavio_io_bench";
    std::filesystem::create_directories(d);
    const std::vector<Event> events = MakeEvents(kEvents);
    {
      auto writer = aavio::io::DsecH5EventWriter::Create((d / "events.h5").string());
      (void)(*writer)->Write(events);
      (void)(*writer)->Close();
    }
    {
      auto writer = aavio::io::BagWriter::Create(
          (d / "events_lz4.bag").string(),
          {.compression = aavio::io::BagCompression::kLz4, .width = 640, .height = 480});
      (void)(*writer)->WriteEvents("/davis/left/events", events);
      (void)(*writer)->Close();
    }
    WriteEvt2((d / "events.raw").string(), events);
    return d.string();
  }();
  return dir;
}

template <typename Open>
void Decode(benchmark::State& state, Open open) {
  std::vector<Event> packet;
  std::size_t total = 0;
  for (auto _ : state) {
    auto stream = open();
    TimeNs t = stream->info().t_first_ns;
    total = 0;
    while (!stream->AtEnd()) {
      packet.clear();
      t += aavio::kNsPerMs;
      if (!stream->ReadUntil(t, &packet).ok()) state.SkipWithError("read failed");
      total += packet.size();
    }
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * total));
}

void BM_DecodeDsecH5(benchmark::State& state) {
  const std::string path = Dir() + "/events.h5";
  Decode(state, [&] { return std::move(*aavio::io::DsecH5EventStream::Open(path, {})); });
}
BENCHMARK(BM_DecodeDsecH5)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DecodeBagLz4(benchmark::State& state) {
  const std::string path = Dir() + "/events_lz4.bag";
  Decode(state, [&] {
    return std::move(*aavio::io::BagEventStream::Open(path, "/davis/left/events", {}));
  });
}
BENCHMARK(BM_DecodeBagLz4)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DecodePropheseeRaw(benchmark::State& state) {
  const std::string path = Dir() + "/events.raw";
  Decode(state, [&] { return std::move(*aavio::io::PropheseeRawEventStream::Open(path, {})); });
}
BENCHMARK(BM_DecodePropheseeRaw)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
