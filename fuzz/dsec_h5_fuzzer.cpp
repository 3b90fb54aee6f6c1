// DSEC-layout HDF5 events (events/{t,x,y,p}, ms_to_idx, t_offset) and rectify_map.h5.
//
// HDF5 1.10 sizes some metadata allocations from the file; a corrupt one asks malloc for hundreds
// of gigabytes, which fails outside a sanitizer (the library then reports an error, as aavio
// does). Here that failure is let through too (allocator_may_return_null, and no per-malloc
// limit), while the memory actually used stays limited by -rss_limit_mb.
#include <cstring>
#include <vector>

#include "aavio/io/formats/dsec_h5/dsec_h5_reader.hpp"
#include "fuzz_input.hpp"

extern "C" const char* __asan_default_options() {
  return "allocator_may_return_null=1";
}

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  static std::vector<char*> args(*argv, *argv + *argc);
  static char no_malloc_limit[] = "-malloc_limit_mb=1000000000";
  args.insert(args.begin() + 1, no_malloc_limit);  // before the corpus folders
  args.push_back(nullptr);
  *argc = static_cast<int>(args.size()) - 1;
  *argv = args.data();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const std::string path = fuzz::WriteInput("events.h5", data, size);
  io::StreamOptions options = fuzz::FuzzStreamOptions();
  options.width = 640;
  options.height = 480;
  if (auto stream = io::DsecH5EventStream::Open(path, options)) fuzz::Drain(**stream);
  (void)io::ReadDsecRectifyMap(path);
  return 0;
}
