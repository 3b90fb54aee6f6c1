#include "aavio/io/prophesee_raw.hpp"

#include <cstdio>
#include <cstring>
#include <string_view>

#include "aavio/common/format.hpp"

namespace aavio::io {

namespace {

enum class RawEncoding { kEvt2, kEvt3 };

struct RawHeader {
  RawEncoding encoding = RawEncoding::kEvt3;
  int width = 0, height = 0;
  long data_offset = 0;
  std::string description;
};

bool Contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

/// Reads the `% ` lines at the start of the file.
Expected<RawHeader> ReadHeader(std::FILE* file, const std::string& path) {
  RawHeader h;
  bool have_encoding = false;
  std::string plugin;
  char line[4096];
  while (true) {
    const long at = std::ftell(file);
    const int c = std::fgetc(file);
    if (c != '%') {
      std::fseek(file, at, SEEK_SET);
      break;
    }
    if (!std::fgets(line, sizeof line, file)) break;
    std::string_view text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
      text.remove_suffix(1);
    if (text == " end") break;
    if (!text.empty() && text.front() == ' ') text.remove_prefix(1);
    if (text.starts_with("evt ")) {
      const std::string_view version = text.substr(4);
      if (version.starts_with("2.0")) {
        h.encoding = RawEncoding::kEvt2, have_encoding = true;
      } else if (version.starts_with("3")) {
        h.encoding = RawEncoding::kEvt3, have_encoding = true;
      } else {
        return InvalidArgument(path + ": RAW encoding 'evt " + std::string(version) +
                               "' is not read; aavio reads EVT 2.0 and EVT 3.0 (convert with "
                               "Metavision's metavision_file_to_hdf5 or re-record in EVT 3.0)");
      }
    } else if (text.starts_with("format ")) {
      const std::string_view format = text.substr(7);
      if (format.starts_with("EVT21")) {
        return InvalidArgument(path +
                               ": RAW encoding EVT 2.1 is not read; aavio reads EVT 2.0 "
                               "and EVT 3.0");
      }
      if (format.starts_with("EVT2")) h.encoding = RawEncoding::kEvt2, have_encoding = true;
      if (format.starts_with("EVT3")) h.encoding = RawEncoding::kEvt3, have_encoding = true;
      int width = 0, height = 0;
      if (const auto w = format.find("width="); w != std::string_view::npos)
        width = std::atoi(std::string(format.substr(w + 6)).c_str());
      if (const auto hh = format.find("height="); hh != std::string_view::npos)
        height = std::atoi(std::string(format.substr(hh + 7)).c_str());
      if (width > 0 && height > 0) h.width = width, h.height = height;
    } else if (text.starts_with("geometry ")) {
      int width = 0, height = 0;
      if (std::sscanf(std::string(text.substr(9)).c_str(), "%dx%d", &width, &height) == 2 &&
          width > 0 && height > 0) {
        h.width = width, h.height = height;
      }
    } else if (text.starts_with("plugin_name ")) {
      plugin = std::string(text.substr(12));
    }
  }
  if (!have_encoding) {
    return InvalidArgument(path +
                           ": no '% evt' or '% format' header line: not a Prophesee RAW "
                           "file (or an EVT 1.0 one, which aavio does not read)");
  }
  if (h.width == 0) {
    // Older files name only the camera plugin; its sensor fixes the geometry.
    if (Contains(plugin, "gen41") || Contains(plugin, "gen4") || Contains(plugin, "imx636") ||
        Contains(plugin, "evk4")) {
      h.width = 1280, h.height = 720;
    } else if (Contains(plugin, "gen3")) {
      h.width = 640, h.height = 480;
    }
  }
  h.data_offset = std::ftell(file);
  h.description =
      StrFormat("Prophesee RAW %s", h.encoding == RawEncoding::kEvt2 ? "EVT 2.0" : "EVT 3.0");
  if (h.width > 0) h.description += StrFormat(", %d x %d", h.width, h.height);
  if (!plugin.empty()) h.description += " (" + plugin + ")";
  return h;
}

/// Word-by-word decoding with the state the encodings carry between words.
class RawDecoder {
 public:
  RawDecoder(RawEncoding encoding, int width, int height, std::string path)
      : encoding_(encoding), width_(width), height_(height), path_(std::move(path)) {}
  std::size_t word_bytes() const { return encoding_ == RawEncoding::kEvt2 ? 4 : 2; }

  /// Decodes whole words of `data` (whose first byte is at `offset` in the file).
  template <typename Emit>
  Status Decode(const unsigned char* data, std::size_t bytes, std::int64_t offset, Emit&& emit) {
    if (encoding_ == RawEncoding::kEvt2) {
      for (std::size_t k = 0; k + 4 <= bytes; k += 4) {
        const std::uint32_t w =
            static_cast<std::uint32_t>(data[k]) | (std::uint32_t{data[k + 1]} << 8) |
            (std::uint32_t{data[k + 2]} << 16) | (std::uint32_t{data[k + 3]} << 24);
        const unsigned type = w >> 28;
        if (type <= 1) {
          if (!have_time_) continue;
          const std::int64_t t_us =
              static_cast<std::int64_t>((time_high_ << 6) | ((w >> 22) & 0x3F));
          AAVIO_RETURN_IF_ERROR(Emit1(t_us, (w >> 11) & 0x7FF, w & 0x7FF, type,
                                      offset + static_cast<std::int64_t>(k), emit));
        } else if (type == 0x8) {
          time_high_ = w & 0x0FFFFFFF;
          have_time_ = true;
        } else if (type != 0xA && type != 0xE && type != 0xF) {
          return Corrupt(type, offset + static_cast<std::int64_t>(k));
        }
      }
      return Status::Ok();
    }
    for (std::size_t k = 0; k + 2 <= bytes; k += 2) {
      const unsigned w = static_cast<unsigned>(data[k]) | (static_cast<unsigned>(data[k + 1]) << 8);
      const unsigned type = w >> 12;
      const std::int64_t at = offset + static_cast<std::int64_t>(k);
      switch (type) {
        case 0x0:
          y_ = w & 0x7FF;
          break;
        case 0x2:
          if (have_time_)
            AAVIO_RETURN_IF_ERROR(Emit1(Evt3Time(), w & 0x7FF, y_, (w >> 11) & 1, at, emit));
          break;
        case 0x3:
          base_x_ = w & 0x7FF;
          polarity_ = (w >> 11) & 1;
          break;
        case 0x4:
        case 0x5: {
          const int bits = type == 0x4 ? 12 : 8;
          if (have_time_) {
            for (int b = 0; b < bits; ++b) {
              if ((w >> b) & 1)
                AAVIO_RETURN_IF_ERROR(
                    Emit1(Evt3Time(), base_x_ + static_cast<unsigned>(b), y_, polarity_, at, emit));
            }
          }
          base_x_ += static_cast<unsigned>(bits);
          break;
        }
        case 0x6:
          time_low_ = w & 0xFFF;
          break;
        case 0x8: {
          const std::uint64_t high = w & 0xFFF;
          if (have_time_ && high < time_high_) ++wraps_;  // the 24-bit time wrapped
          time_high_ = high;
          have_time_ = true;
          break;
        }
        case 0x7:
        case 0xA:
        case 0xE:
        case 0xF:
          break;
        default:
          return Corrupt(type, at);
      }
    }
    return Status::Ok();
  }

 private:
  std::int64_t Evt3Time() const {
    return static_cast<std::int64_t>((wraps_ << 24) | (time_high_ << 12) | time_low_);
  }
  template <typename Emit>
  Status Emit1(std::int64_t t_us, unsigned x, unsigned y, unsigned polarity, std::int64_t at,
               Emit& emit) {
    if (width_ > 0 && (x >= static_cast<unsigned>(width_) || y >= static_cast<unsigned>(height_))) {
      return InvalidArgument(
          StrFormat("%s: event at (%u, %u) outside the %d x %d sensor, byte %lld: "
                    "a corrupt file, or a header with the wrong geometry",
                    path_.c_str(), x, y, width_, height_, static_cast<long long>(at)));
    }
    emit(events::Event{t_us * kNsPerUs, static_cast<std::uint16_t>(x),
                       static_cast<std::uint16_t>(y), static_cast<std::uint8_t>(polarity)},
         at);
    return Status::Ok();
  }
  Status Corrupt(unsigned type, std::int64_t at) const {
    return InvalidArgument(
        StrFormat("%s: word type 0x%X at byte %lld is not %s: a corrupt file, or "
                  "one whose header names the wrong encoding",
                  path_.c_str(), type, static_cast<long long>(at),
                  encoding_ == RawEncoding::kEvt2 ? "EVT 2.0" : "EVT 3.0"));
  }

  RawEncoding encoding_;
  int width_, height_;
  std::string path_;
  bool have_time_ = false;
  std::uint64_t time_high_ = 0, time_low_ = 0, wraps_ = 0;
  unsigned y_ = 0, base_x_ = 0, polarity_ = 0;
};

constexpr std::size_t kBlockBytes = 1 << 20;

}  // namespace

struct PropheseeRawEventStream::State {
  std::string path;
  std::FILE* file = nullptr;
  RawHeader header;
  StreamInfo info;
  RawDecoder decoder{RawEncoding::kEvt3, 0, 0, ""};
  ReorderBuffer<events::Event> reorder{0};
  std::vector<unsigned char> block;
  std::int64_t position = 0;  // file offset of the next byte to decode
  bool exhausted = false;
  ~State() {
    if (file) std::fclose(file);
  }

  void Rewind() {
    std::fseek(file, header.data_offset, SEEK_SET);
    position = header.data_offset;
    decoder = RawDecoder(header.encoding, header.width, header.height, path);
    exhausted = false;
  }
  /// Decodes the next block; `emit(event, byte)`.
  template <typename Emit>
  Status NextBlock(Emit&& emit) {
    block.resize(kBlockBytes);
    const std::size_t got = std::fread(block.data(), 1, block.size(), file);
    if (got == 0) {
      if (std::ferror(file))
        return IoError(path + ": read error at byte " + std::to_string(position));
      exhausted = true;
      return Status::Ok();
    }
    const std::size_t word = decoder.word_bytes();
    const std::size_t whole = got / word * word;
    if (whole < got && std::feof(file)) {
      return InvalidArgument(StrFormat(
          "%s: the file ends inside a %zu-byte word (byte %lld): "
          "truncated",
          path.c_str(), word, static_cast<long long>(position + static_cast<std::int64_t>(whole))));
    }
    AAVIO_RETURN_IF_ERROR(decoder.Decode(block.data(), whole, position, emit));
    if (whole < got) std::fseek(file, static_cast<long>(whole) - static_cast<long>(got), SEEK_CUR);
    position += static_cast<std::int64_t>(whole);
    return Status::Ok();
  }
};

PropheseeRawEventStream::PropheseeRawEventStream(std::unique_ptr<State> s) : s_(std::move(s)) {}
PropheseeRawEventStream::~PropheseeRawEventStream() = default;

Expected<std::unique_ptr<PropheseeRawEventStream>> PropheseeRawEventStream::Open(
    const std::string& path, const StreamOptions& options) {
  auto s = std::make_unique<State>();
  s->path = path;
  s->file = std::fopen(path.c_str(), "rb");
  if (!s->file) return IoError(path + ": cannot open (" + std::strerror(errno) + ")");
  Expected<RawHeader> header = ReadHeader(s->file, path);
  if (!header) return header.status();
  s->header = *header;
  if (options.width > 0) {
    if (s->header.width > 0 &&
        (s->header.width != options.width || s->header.height != options.height)) {
      return InvalidArgument(
          StrFormat("%s: the file's sensor is %d x %d, the calibration's %d x %d", path.c_str(),
                    s->header.width, s->header.height, options.width, options.height));
    }
    s->header.width = options.width, s->header.height = options.height;
  }
  s->info.description = s->header.description + ": " + path;
  s->info.width = s->header.width;
  s->info.height = s->header.height;
  // One pass: the count and time range, and every word checked.
  s->Rewind();
  std::int64_t count = 0;
  TimeNs first = 0, last = 0;
  while (!s->exhausted) {
    AAVIO_RETURN_IF_ERROR(s->NextBlock([&](const events::Event& e, std::int64_t) {
      if (count == 0) first = last = e.t_ns;
      last = std::max(last, e.t_ns);
      ++count;
    }));
  }
  s->info.count = count;
  s->info.t_first_ns = first;
  s->info.t_last_ns = last;
  s->reorder = ReorderBuffer<events::Event>(options.max_reorder_ns);
  s->Rewind();
  return std::unique_ptr<PropheseeRawEventStream>(new PropheseeRawEventStream(std::move(s)));
}

const StreamInfo& PropheseeRawEventStream::info() const {
  return s_->info;
}

Status PropheseeRawEventStream::ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out) {
  Status pushed = Status::Ok();
  while (!s_->reorder.CanRelease(t_end_ns) && !s_->exhausted && pushed.ok()) {
    AAVIO_RETURN_IF_ERROR(s_->NextBlock([&](const events::Event& e, std::int64_t at) {
      if (pushed.ok()) pushed = s_->reorder.Push(e, s_->path + ", byte " + std::to_string(at));
    }));
  }
  AAVIO_RETURN_IF_ERROR(pushed);
  s_->reorder.Release(t_end_ns, out);
  return Status::Ok();
}

Status PropheseeRawEventStream::Seek(TimeNs t_ns) {
  s_->Rewind();
  s_->reorder.Reset(t_ns);
  return Status::Ok();
}

bool PropheseeRawEventStream::AtEnd() const {
  return s_->exhausted && s_->reorder.size() == 0;
}

}  // namespace aavio::io
