// Prophesee RAW files: the `%` header and EVT 2.0 / EVT 3.0 words.
#include "aavio/io/formats/prophesee_raw/prophesee_raw.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const std::string path = fuzz::WriteInput("input.raw", data, size);
  if (auto events = io::PropheseeRawEventStream::Open(path, fuzz::FuzzStreamOptions())) {
    fuzz::Drain(**events);
  }
  return 0;
}
