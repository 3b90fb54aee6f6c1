#pragma once
/// The Event Camera Dataset's text layout (docs/io.md), streamed in blocks:
///   events.txt  `t x y p`                 (t in seconds, p 0/1)
///   imu.txt     `t ax ay az gx gy gz`     (ECD: accelerometer first, seconds)
///               or `t_us gx gy gz ax ay az` (TUM-VIE: gyroscope first, µs)
/// `#` lines and blank lines are skipped; columns may be separated by spaces, tabs or commas.
/// Seeking re-reads from the start (text has no index).

#include <cstdio>
#include <memory>
#include <span>
#include <string>

#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/io/streams.hpp"

namespace aavio::io {

enum class ImuTextLayout {
  kEcd,     ///< t[s] ax ay az gx gy gz
  kTumVie,  ///< t[µs] gx gy gz ax ay az
};

struct TextEventDecoder;  // the format's decoder (text_streams.cpp)

class TextEventStream final : public DecodedStream<events::Event, TextEventDecoder> {
 public:
  static Expected<std::unique_ptr<TextEventStream>> Open(const std::string& path,
                                                         const StreamOptions& options);
  ~TextEventStream() override;

 private:
  using DecodedStream::DecodedStream;
};

struct TextImuDecoder;  // the format's decoder (text_streams.cpp)

class TextImuStream final : public DecodedStream<imu::ImuSample, TextImuDecoder> {
 public:
  static Expected<std::unique_ptr<TextImuStream>> Open(const std::string& path,
                                                       ImuTextLayout layout,
                                                       const StreamOptions& options);
  ~TextImuStream() override;

 private:
  using DecodedStream::DecodedStream;
};

/// Writes events.txt (`t x y p`, 9-decimal seconds), streaming.
class TextEventWriter {
 public:
  static Expected<std::unique_ptr<TextEventWriter>> Create(const std::string& path);
  ~TextEventWriter();
  Status Write(std::span<const events::Event> events);
  Status Close();

 private:
  TextEventWriter(std::string path, std::FILE* file) : path_(std::move(path)), file_(file) {}
  std::string path_;
  std::FILE* file_;
};

/// Writes imu.txt in the ECD layout (`t ax ay az gx gy gz`) with a `#` header.
Status WriteImuText(const std::string& path, std::span<const imu::ImuSample> samples);

}  // namespace aavio::io
