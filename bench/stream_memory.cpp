// Peak memory of streaming a large file: `stream_memory write DIR N` writes N events as a
// DSEC-layout events.h5 and an lz4 bag; `stream_memory read FILE` streams a file in 1 ms packets
// and prints the peak resident set size (run under /usr/bin/time -v to cross-check).
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "aavio/io/formats/dsec_h5/dsec_h5_writer.hpp"
#include "aavio/io/formats/rosbag/bag_writer.hpp"
#include "aavio/io/sequence.hpp"

namespace {

long PeakRssKb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

int Write(const std::string& dir, std::size_t n) {
  std::filesystem::create_directories(dir);
  auto h5 = aavio::io::DsecH5EventWriter::Create(dir + "/events.h5");
  auto bag = aavio::io::BagWriter::Create(
      dir + "/events_lz4.bag",
      {.compression = aavio::io::BagCompression::kLz4, .width = 640, .height = 480});
  if (!h5.ok() || !bag.ok()) return 1;
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> col(0, 639), row(0, 479), gap(0, 400);
  std::vector<aavio::events::Event> block;
  aavio::TimeNs t = 36470123457LL * 1000;
  for (std::size_t written = 0; written < n;) {
    block.clear();
    for (std::size_t i = 0; i < 1'000'000 && written < n; ++i, ++written) {
      t += gap(rng);
      block.push_back({t, static_cast<std::uint16_t>(col(rng)),
                       static_cast<std::uint16_t>(row(rng)), static_cast<std::uint8_t>(i & 1)});
    }
    if (!(*h5)->Write(block).ok() || !(*bag)->WriteEvents("/davis/left/events", block).ok())
      return 1;
  }
  if (!(*h5)->Close().ok() || !(*bag)->Close().ok()) return 1;
  std::printf("wrote %zu events to %s (peak RSS %ld MB)\n", n, dir.c_str(), PeakRssKb() / 1024);
  return 0;
}

int Read(const std::string& path) {
  aavio::io::SourceSpec spec{*aavio::io::DetectSourceFormat(path), path, "/davis/left/events", {}};
  auto stream = aavio::io::OpenEventStream(spec, {});
  if (!stream.ok()) {
    std::fprintf(stderr, "%s\n", stream.status().message().c_str());
    return 1;
  }
  const long before_kb = PeakRssKb();
  std::vector<aavio::events::Event> packet;
  aavio::TimeNs t = (*stream)->info().t_first_ns;
  std::size_t total = 0;
  while (!(*stream)->AtEnd()) {
    packet.clear();
    t += aavio::kNsPerMs;
    if (!(*stream)->ReadUntil(t, &packet).ok()) return 1;
    total += packet.size();
  }
  std::printf("%s: streamed %zu events; peak RSS %ld MB (after opening: %ld MB)\n", path.c_str(),
              total, PeakRssKb() / 1024, before_kb / 1024);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "write") return Write(argv[2], std::stoull(argv[3]));
  if (argc == 3 && std::string(argv[1]) == "read") return Read(argv[2]);
  std::fprintf(stderr, "usage: stream_memory write DIR N | stream_memory read FILE\n");
  return 2;
}
