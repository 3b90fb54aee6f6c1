#include "aavio/io/formats/prophesee_raw/prophesee_raw.hpp"

#include <cstdio>
#include <cstring>
#include <string_view>

#include "aavio/common/format.hpp"
#include "aavio/io/decoded_stream_impl.hpp"
#include "aavio/io/event_codecs.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::io {

namespace {

struct RawHeader {
  EventEncoding encoding = EventEncoding::kEvt3;
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
        h.encoding = EventEncoding::kEvt2, have_encoding = true;
      } else if (version.starts_with("3")) {
        h.encoding = EventEncoding::kEvt3, have_encoding = true;
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
      if (format.starts_with("EVT2")) h.encoding = EventEncoding::kEvt2, have_encoding = true;
      if (format.starts_with("EVT3")) h.encoding = EventEncoding::kEvt3, have_encoding = true;
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
      StrFormat("Prophesee RAW %s", h.encoding == EventEncoding::kEvt2 ? "EVT 2.0" : "EVT 3.0");
  if (h.width > 0) h.description += StrFormat(", %d x %d", h.width, h.height);
  if (!plugin.empty()) h.description += " (" + plugin + ")";
  return h;
}

constexpr std::size_t kBlockBytes = 1 << 20;

}  // namespace

struct PropheseeRawDecoder {
  std::string path;
  std::FILE* file = nullptr;
  RawHeader header;
  StreamInfo info;
  EventWordDecoder decoder{EventEncoding::kEvt3, 0, 0, ""};
  ReorderBuffer<events::Event> reorder{0};
  std::vector<unsigned char> block;
  std::int64_t position = 0;  // file offset of the next byte to decode
  bool exhausted = false;
  ~PropheseeRawDecoder() {
    if (file) std::fclose(file);
  }

  void Rewind() {
    std::fseek(file, header.data_offset, SEEK_SET);
    position = header.data_offset;
    decoder = EventWordDecoder(header.encoding, header.width, header.height, path);
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

  Status ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out) {
    Status pushed = Status::Ok();
    while (!reorder.CanRelease(t_end_ns) && !exhausted && pushed.ok()) {
      AAVIO_RETURN_IF_ERROR(NextBlock([&](const events::Event& e, std::int64_t at) {
        if (!pushed.ok()) return;
        pushed = reorder.PushDescribed(e, [&] { return path + ", byte " + std::to_string(at); });
      }));
    }
    AAVIO_RETURN_IF_ERROR(pushed);
    reorder.Release(t_end_ns, out);
    return Status::Ok();
  }
  Status Seek(TimeNs t_ns) {
    Rewind();
    reorder.Reset(t_ns);
    return Status::Ok();
  }
  bool AtEnd() const { return exhausted && reorder.size() == 0; }
};

template class DecodedStream<events::Event, PropheseeRawDecoder>;

PropheseeRawEventStream::~PropheseeRawEventStream() = default;

Expected<std::unique_ptr<PropheseeRawEventStream>> PropheseeRawEventStream::Open(
    const std::string& path, const StreamOptions& options) {
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "Prophesee RAW file"));
  auto s = std::make_unique<PropheseeRawDecoder>();
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

}  // namespace aavio::io
