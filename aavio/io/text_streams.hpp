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

class TextEventStream final : public EventStream {
 public:
  static Expected<std::unique_ptr<TextEventStream>> Open(const std::string& path,
                                                         const StreamOptions& options);
  ~TextEventStream() override;
  const StreamInfo& info() const override;
  Status ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out) override;
  Status Seek(TimeNs t_ns) override;
  bool AtEnd() const override;

 private:
  struct State;
  explicit TextEventStream(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

class TextImuStream final : public ImuStream {
 public:
  static Expected<std::unique_ptr<TextImuStream>> Open(const std::string& path,
                                                       ImuTextLayout layout,
                                                       const StreamOptions& options);
  ~TextImuStream() override;
  const StreamInfo& info() const override;
  Status ReadUntil(TimeNs t_end_ns, std::vector<imu::ImuSample>* out) override;
  Status Seek(TimeNs t_ns) override;
  bool AtEnd() const override;

 private:
  struct State;
  explicit TextImuStream(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
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
