#include "aavio/io/formats/text/text_streams.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "aavio/common/format.hpp"
#include "aavio/io/decoded_stream_impl.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/text_fields.hpp"

namespace aavio::io {

namespace {

using text::IsSeparator;
using text::IsSkipped;
using text::ParseNumber;
using text::SplitFields;

/// Reads a text file line by line in large blocks; remembers line numbers.
class LineReader {
 public:
  Status Open(const std::string& path) {
    AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "text data file"));
    path_ = path;
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) return NotFound(path + ": cannot open");
    // Blocks of 4 MB, or the whole file if smaller.
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    buffer_.resize(ec ? kBlockBytes : std::clamp<std::size_t>(size + 1, 4096, kBlockBytes));
    begin_ = end_ = 0;
    line_ = 0;
    eof_ = false;
    return Status::Ok();
  }
  ~LineReader() {
    if (file_) std::fclose(file_);
  }
  void Rewind() {
    std::fseek(file_, 0, SEEK_SET);
    begin_ = end_ = 0;
    line_ = 0;
    eof_ = false;
  }
  /// The next line without its newline; false at the end of the file.
  bool Next(std::string_view* line) {
    while (true) {
      const char* start = buffer_.data() + begin_;
      const void* nl = std::memchr(start, '\n', end_ - begin_);
      if (nl) {
        const std::size_t len = static_cast<const char*>(nl) - start;
        *line = std::string_view(start, len);
        begin_ += len + 1;
        ++line_;
        return true;
      }
      if (eof_) {
        if (begin_ == end_) return false;
        *line = std::string_view(start, end_ - begin_);  // last line without a newline
        begin_ = end_;
        ++line_;
        return true;
      }
      // Move the partial line to the front and read more.
      std::memmove(buffer_.data(), start, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
      if (end_ == buffer_.size()) {
        // A line longer than a block is no line of these formats (a binary file, say): it is
        // returned whole, for the parser to refuse it with its line number.
        if (buffer_.size() >= kBlockBytes) {
          *line = std::string_view(buffer_.data(), end_);
          begin_ = end_;
          ++line_;
          return true;
        }
        buffer_.resize(std::min(buffer_.size() * 2, kBlockBytes));
      }
      const std::size_t n = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
      end_ += n;
      if (n == 0) eof_ = true;
    }
  }
  std::string Where() const { return path_ + ":" + std::to_string(line_); }
  std::FILE* file() const { return file_; }

 private:
  static constexpr std::size_t kBlockBytes = 4 << 20;
  std::string path_;
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;
  std::size_t line_ = 0;
  bool eof_ = false;
};

Status ParseEventLine(std::string_view line, const std::string& where, const StreamOptions& options,
                      events::Event* e) {
  std::array<std::string_view, 4> f;
  const std::size_t n = SplitFields(line, &f);
  if (n != 4) {
    return ParseError(where + ": expected 4 columns 't x y p', found " + std::to_string(n));
  }
  Expected<TimeNs> t = ParseSecondsToNs(f[0]);
  if (!t) return ParseError(where + ": " + t.status().message());
  int x = 0, y = 0, p = 0;
  if (!ParseNumber(f[1], &x) || !ParseNumber(f[2], &y) || !ParseNumber(f[3], &p) || x < 0 ||
      y < 0 || x > 65535 || y > 65535) {
    return ParseError(where + ": x and y must be integers from 0 to 65535 and p an integer, got '" +
                      PrintableExcerpt(line) + "'");
  }
  // 0/1 as the Event Camera Dataset writes it, or -1/1 as some converters do.
  if (p < -1 || p > 1) {
    return ParseError(where + ": polarity p = " + std::to_string(p) +
                      " is none of 0 or -1 (OFF) and 1 (ON); is the column order 't x y p'?");
  }
  if (options.width > 0 && (x >= options.width || y >= options.height)) {
    return InvalidArgument(where + ": event at (" + std::to_string(x) + ", " + std::to_string(y) +
                           ") is outside the " + std::to_string(options.width) + "x" +
                           std::to_string(options.height) +
                           " sensor; does the calibration belong to this recording?");
  }
  *e = {*t, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y),
        static_cast<std::uint8_t>(p > 0 ? 1 : 0)};
  return Status::Ok();
}

Status ParseImuLine(std::string_view line, const std::string& where, ImuTextLayout layout,
                    imu::ImuSample* sample) {
  std::array<std::string_view, 8> f;
  const std::size_t n = SplitFields(line, &f);
  if (n < 7) {
    return ParseError(
        where + ": expected 7 columns (" +
        (layout == ImuTextLayout::kEcd ? "t ax ay az gx gy gz" : "t_us gx gy gz ax ay az") +
        "), found " + std::to_string(n));
  }
  TimeNs t_ns = 0;
  if (layout == ImuTextLayout::kEcd) {
    Expected<TimeNs> t = ParseSecondsToNs(f[0]);
    if (!t) return ParseError(where + ": " + t.status().message());
    t_ns = *t;
  } else {
    std::int64_t t_us = 0;
    if (!ParseNumber(f[0], &t_us)) return ParseError(where + ": t_us must be an integer");
    if (!MicrosecondsToNs(t_us, 0, &t_ns)) {
      return ParseError(where + ": t_us = " + std::string(f[0]) +
                        " is beyond what nanoseconds hold (292 years)");
    }
  }
  std::array<double, 6> v{};
  for (int k = 0; k < 6; ++k) {
    if (!ParseNumber(f[k + 1], &v[k]) || !std::isfinite(v[k])) {
      return ParseError(where + ": column " + std::to_string(k + 2) + " = '" +
                        std::string(f[k + 1]) + "' is not a finite number");
    }
  }
  sample->t_ns = t_ns;
  if (layout == ImuTextLayout::kEcd) {
    sample->accel_m_s2 = {v[0], v[1], v[2]};
    sample->gyro_rad_s = {v[3], v[4], v[5]};
  } else {
    sample->gyro_rad_s = {v[0], v[1], v[2]};
    sample->accel_m_s2 = {v[3], v[4], v[5]};
  }
  return Status::Ok();
}

/// The last non-comment line of a file (read from its tail), for the info of a text stream.
std::string LastDataLine(std::FILE* file) {
  std::fseek(file, 0, SEEK_END);
  const long size = std::ftell(file);
  const long from = std::max(0L, size - 4096);
  std::fseek(file, from, SEEK_SET);
  std::string tail(static_cast<std::size_t>(size - from), '\0');
  tail.resize(std::fread(tail.data(), 1, tail.size(), file));
  std::fseek(file, 0, SEEK_SET);
  std::size_t end = tail.size();
  while (end > 0) {
    std::size_t begin = tail.rfind('\n', end - 1);
    begin = begin == std::string::npos ? 0 : begin + 1;
    const std::string_view line(tail.data() + begin, end - begin);
    if (!IsSkipped(line) && (begin > 0 || from == 0)) return std::string(line);
    if (begin == 0) break;
    end = begin - 1;
  }
  return {};
}

/// Shared machinery of the two text streams: read lines, parse, reorder, release.
template <typename T, typename Parse>
struct TextStreamCore {
  LineReader lines;
  StreamInfo info;
  ReorderBuffer<T> reorder{0};
  bool exhausted = false;
  Parse parse;

  Status Fill(TimeNs t_end_ns) {
    std::string_view line;
    std::size_t read = 0;
    while (!reorder.CanRelease(t_end_ns) && !exhausted) {
      if (!lines.Next(&line)) {
        exhausted = true;
        break;
      }
      if (IsSkipped(line)) continue;
      T element;
      AAVIO_RETURN_IF_ERROR(parse(line, lines.Where(), &element));
      AAVIO_RETURN_IF_ERROR(reorder.Push(element, lines.Where()));
      ++read;
    }
    (void)read;
    return Status::Ok();
  }
  Status ReadUntil(TimeNs t_end_ns, std::vector<T>* out) {
    AAVIO_RETURN_IF_ERROR(Fill(t_end_ns));
    reorder.Release(t_end_ns, out);
    return Status::Ok();
  }
  Status Seek(TimeNs t_ns) {
    lines.Rewind();
    exhausted = false;
    reorder.Reset(t_ns);
    return Status::Ok();
  }
  bool AtEnd() const { return exhausted && reorder.size() == 0; }
  /// First and last stamps for the info, from the head and the tail of the file.
  Status ReadEnds() {
    std::string_view line;
    while (lines.Next(&line)) {
      if (IsSkipped(line)) continue;
      T first;
      AAVIO_RETURN_IF_ERROR(parse(line, lines.Where(), &first));
      info.t_first_ns = first.t_ns;
      const std::string last_line = LastDataLine(lines.file());
      T last;
      if (parse(last_line, "last line", &last).ok()) info.t_last_ns = last.t_ns;
      info.count = -1;
      break;
    }
    lines.Rewind();
    return Status::Ok();
  }
};

struct EventParse {
  StreamOptions options;
  Status operator()(std::string_view line, const std::string& where, events::Event* e) const {
    return ParseEventLine(line, where, options, e);
  }
};

struct ImuParse {
  ImuTextLayout layout;
  Status operator()(std::string_view line, const std::string& where, imu::ImuSample* s) const {
    return ParseImuLine(line, where, layout, s);
  }
};

}  // namespace

struct TextEventDecoder : TextStreamCore<events::Event, EventParse> {};
template class DecodedStream<events::Event, TextEventDecoder>;

struct TextImuDecoder : TextStreamCore<imu::ImuSample, ImuParse> {};
template class DecodedStream<imu::ImuSample, TextImuDecoder>;

TextEventStream::~TextEventStream() = default;

Expected<std::unique_ptr<TextEventStream>> TextEventStream::Open(const std::string& path,
                                                                 const StreamOptions& options) {
  auto s = std::make_unique<TextEventDecoder>();
  AAVIO_RETURN_IF_ERROR(s->lines.Open(path));
  s->parse.options = options;
  s->reorder = ReorderBuffer<events::Event>(options.max_reorder_ns);
  s->info.description = "events text: " + path;
  AAVIO_RETURN_IF_ERROR(s->ReadEnds());
  return std::unique_ptr<TextEventStream>(new TextEventStream(std::move(s)));
}

TextImuStream::~TextImuStream() = default;

Expected<std::unique_ptr<TextImuStream>> TextImuStream::Open(const std::string& path,
                                                             ImuTextLayout layout,
                                                             const StreamOptions& options) {
  auto s = std::make_unique<TextImuDecoder>();
  AAVIO_RETURN_IF_ERROR(s->lines.Open(path));
  s->parse.layout = layout;
  s->reorder = ReorderBuffer<imu::ImuSample>(options.max_reorder_ns);
  s->info.description = "IMU text: " + path;
  AAVIO_RETURN_IF_ERROR(s->ReadEnds());
  return std::unique_ptr<TextImuStream>(new TextImuStream(std::move(s)));
}

Expected<std::unique_ptr<TextEventWriter>> TextEventWriter::Create(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return IoError(path + ": cannot open for writing");
  std::fputs("# t[s] x y p\n", file);
  return std::unique_ptr<TextEventWriter>(new TextEventWriter(path, file));
}

TextEventWriter::~TextEventWriter() {
  (void)Close();
}

Status TextEventWriter::Write(std::span<const events::Event> events) {
  if (!file_) return FailedPrecondition(path_ + ": writer already closed");
  std::string out;
  out.reserve(events.size() * 28);
  char line[64];
  for (const events::Event& e : events) {
    out += FormatSecondsNs(e.t_ns);
    const int n = std::snprintf(line, sizeof(line), " %u %u %u\n", e.x, e.y, e.polarity ? 1u : 0u);
    out.append(line, static_cast<std::size_t>(n));
  }
  if (std::fwrite(out.data(), 1, out.size(), file_) != out.size()) {
    return IoError(path_ + ": write failed (disk full?)");
  }
  return Status::Ok();
}

Status TextEventWriter::Close() {
  if (!file_) return Status::Ok();
  const bool ok = std::fclose(file_) == 0;
  file_ = nullptr;
  return ok ? Status::Ok() : IoError(path_ + ": closing failed (disk full?)");
}

Status WriteImuText(const std::string& path, std::span<const imu::ImuSample> samples) {
  std::string out = "# t[s] ax ay az[m/s^2] gx gy gz[rad/s]\n";
  for (const imu::ImuSample& s : samples) {
    out += FormatSecondsNs(s.t_ns);
    out += StrFormat(" %.9g %.9g %.9g %.9g %.9g %.9g\n", s.accel_m_s2.x(), s.accel_m_s2.y(),
                     s.accel_m_s2.z(), s.gyro_rad_s.x(), s.gyro_rad_s.y(), s.gyro_rad_s.z());
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return IoError(path + ": cannot open for writing");
  const bool ok = std::fwrite(out.data(), 1, out.size(), file) == out.size();
  return (std::fclose(file) == 0 && ok) ? Status::Ok() : IoError(path + ": write failed");
}

}  // namespace aavio::io
