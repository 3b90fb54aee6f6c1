#pragma once
/// Streaming reader of DSEC-layout event files (docs/io.md): /events/{x,y,p,t} with an int64
/// /t_offset [µs] (scalar or shape (1,); absent in TUM-VIE files, whose t is int64 µs), and
/// /ms_to_idx for seeking. Any integer dtypes are accepted. Reads blocks with hyperslabs, so
/// memory stays at one block plus the reorder window whatever the file size.

#include <memory>
#include <string>
#include <vector>

#include "aavio/io/streams.hpp"

namespace aavio::io {

struct DsecH5Decoder;  // the format's decoder (dsec_h5_reader.cpp)

class DsecH5EventStream final : public DecodedStream<events::Event, DsecH5Decoder> {
 public:
  static Expected<std::unique_ptr<DsecH5EventStream>> Open(const std::string& path,
                                                           const StreamOptions& options);
  ~DsecH5EventStream() override;

  /// Events per millisecond of the file, from ms_to_idx (empty when the file has none or it is
  /// inconsistent): the event-rate profile without reading the events.
  const std::vector<std::uint64_t>& ms_to_idx() const;
  std::int64_t t_offset_us() const;

 private:
  using DecodedStream::DecodedStream;
  /// Open without the crash probe.
  static Expected<std::unique_ptr<DsecH5EventStream>> OpenHere(const std::string& path,
                                                               const StreamOptions& options);
};

}  // namespace aavio::io

#include <opencv2/core/mat.hpp>

namespace aavio::io {

/// DSEC rectify_map.h5 (docs/io.md): /rectify_map float32 (height, width, 2), the rectified
/// position of every raw pixel. Returned as CV_32FC2, the layout of RectificationMaps::event_lut.
Expected<cv::Mat> ReadDsecRectifyMap(const std::string& path);

}  // namespace aavio::io
