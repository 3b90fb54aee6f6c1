#pragma once
/// Writes events in the DSEC events.h5 layout (docs/io.md), streaming: /events/{x u2, y u2,
/// p u1, t u4} relative to an int64 scalar /t_offset [µs], and /ms_to_idx (u8) with
/// ms_to_idx[ms] = first event with t >= 1000·ms. Datasets are chunked and compressed with blosc
/// (zstd, bit-shuffle), as the DSEC authors' writers do. Timestamps are stored in µs (rounded).

#include <memory>
#include <optional>
#include <span>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/events/event.hpp"

namespace aavio::io {

struct DsecH5WriterOptions {
  bool compress = true;       ///< blosc/zstd/bit-shuffle; false writes uncompressed chunks
  int compression_level = 1;  ///< blosc clevel (DSEC writers use 1)
  std::size_t chunk_events = 1 << 16;
  /// /t_offset [µs]; by default the first event's time, rounded down to the millisecond.
  std::optional<std::int64_t> t_offset_us;
};

class DsecH5EventWriter {
 public:
  static Expected<std::unique_ptr<DsecH5EventWriter>> Create(
      const std::string& path, const DsecH5WriterOptions& options = {});
  ~DsecH5EventWriter();  ///< closes (errors at this point are lost: call Close)

  /// Appends events; times must not decrease across calls.
  Status Write(std::span<const events::Event> events);
  /// Writes ms_to_idx and t_offset and closes the file.
  Status Close();

 private:
  struct State;
  explicit DsecH5EventWriter(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

}  // namespace aavio::io
