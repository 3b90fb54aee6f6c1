#pragma once
/// Prophesee RAW event files (Metavision recordings, `.raw`), EVT 2.0 and EVT 3.0 (docs/io.md):
/// an ASCII header of lines starting with `% ` — the encoding (`% evt 3.0` or
/// `% format EVT3;height=720;width=1280`), the geometry when stated, the camera plugin — then
/// little-endian words:
///   EVT 2.0  32-bit: type in bits 31..28 — 0 CD_OFF / 1 CD_ON (t[5:0] bits 27..22, x 21..11,
///            y 10..0), 8 TIME_HIGH (t[33:6]), 0xA trigger, 0xE / 0xF vendor words;
///   EVT 3.0  16-bit: type in bits 15..12 — 0 ADDR_Y, 2 ADDR_X (polarity bit 11), 3 VECT_BASE_X,
///            4 VECT_12 / 5 VECT_8 (a bit mask of events from the base x on), 6 TIME_LOW,
///            8 TIME_HIGH (24-bit µs time, unwrapped here), 7 / 0xA / 0xE / 0xF other words.
/// Events before the first TIME_HIGH have no time and are skipped, as Metavision does. EVT 3.0's
/// TIME_LOW may step back by a few µs; such events are put in place by the reorder window.
/// The whole file is decoded once when opened (count and time range; a corrupt or truncated file
/// fails there, naming the byte), then streamed in blocks.

#include <memory>
#include <string>

#include "aavio/io/streams.hpp"

namespace aavio::io {

struct PropheseeRawDecoder;  // the format's decoder (prophesee_raw.cpp)

class PropheseeRawEventStream final : public DecodedStream<events::Event, PropheseeRawDecoder> {
 public:
  static Expected<std::unique_ptr<PropheseeRawEventStream>> Open(const std::string& path,
                                                                 const StreamOptions& options);
  ~PropheseeRawEventStream() override;

 private:
  using DecodedStream::DecodedStream;
};

}  // namespace aavio::io
