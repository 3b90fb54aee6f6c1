#include "aavio/io/formats/aedat4/aedat4.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <string_view>
#include <vector>

#include "aavio/common/format.hpp"
#include "aavio/io/decompression.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::io {

namespace {

constexpr std::string_view kMagic = "#!AER-DAT4.0\r\n";
constexpr double kStandardGravity = 9.80665;  // DV's accelerometer unit, g
constexpr double kDegToRad = std::numbers::pi / 180.0;

enum class Compression { kNone = 0, kLz4 = 1, kLz4High = 2, kZstd = 3, kZstdHigh = 4 };

/// Bounds-checked reads of a flatbuffer (little-endian tables with vtables, vectors, strings).
class FlatBuffer {
 public:
  FlatBuffer(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool U32(std::size_t at, std::uint32_t* v) const { return Read(at, v); }
  template <typename T>
  bool Read(std::size_t at, T* v) const {
    if (at > size_ || size_ - at < sizeof(T)) return false;
    std::memcpy(v, data_ + at, sizeof(T));
    return true;
  }
  /// Position of the root table (the buffer's first word is its offset).
  bool Root(std::size_t* table) const {
    std::uint32_t off = 0;
    if (!U32(0, &off)) return false;
    *table = off;
    return *table < size_;
  }
  /// Position of field `index` of the table at `table`; false if absent or out of bounds.
  bool Field(std::size_t table, int index, std::size_t* at) const {
    std::int32_t soffset = 0;
    if (!Read(table, &soffset)) return false;
    const std::int64_t vtable = static_cast<std::int64_t>(table) - soffset;
    std::uint16_t vsize = 0, field = 0;
    if (vtable < 0 || !Read(static_cast<std::size_t>(vtable), &vsize)) return false;
    const std::size_t entry = 4 + 2 * static_cast<std::size_t>(index);
    if (entry + 2 > vsize || !Read(static_cast<std::size_t>(vtable) + entry, &field) || field == 0)
      return false;
    *at = table + field;
    return *at < size_;
  }
  /// The vector (or string) a field points to: first element and length; false if malformed.
  bool Vector(std::size_t field_at, std::size_t element_size, std::size_t* first,
              std::size_t* length) const {
    std::uint32_t off = 0, n = 0;
    if (!U32(field_at, &off) || !U32(field_at + off, &n)) return false;
    *first = field_at + off + 4;
    *length = n;
    return *first <= size_ && (size_ - *first) / element_size >= n;
  }
  /// Table element i of a vector of tables.
  bool TableAt(std::size_t first, std::size_t i, std::size_t* table) const {
    std::uint32_t off = 0;
    const std::size_t at = first + 4 * i;
    if (!U32(at, &off)) return false;
    *table = at + off;
    return *table < size_;
  }
  template <typename T>
  T Scalar(std::size_t table, int index, T fallback) const {
    std::size_t at = 0;
    T v = fallback;
    if (Field(table, index, &at) && Read(at, &v)) return v;
    return fallback;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

struct StreamDescription {
  int id = -1;
  std::string type;  // EVTS, IMUS, FRME, TRIG, ...
  std::string module, output;
  int width = 0, height = 0;
};

struct Packet {
  std::int64_t offset = 0;  // of the compressed data, after the 8-byte packet header
  std::int32_t size = 0;
};

/// The value of `<attr key="KEY" ...>VALUE</attr>` in `node`, or "".
std::string Attribute(std::string_view node, std::string_view key) {
  const std::string pattern = "key=\"" + std::string(key) + "\"";
  const std::size_t at = node.find(pattern);
  if (at == std::string_view::npos) return "";
  const std::size_t begin = node.find('>', at);
  const std::size_t end = node.find('<', begin);
  if (begin == std::string_view::npos || end == std::string_view::npos) return "";
  return std::string(node.substr(begin + 1, end - begin - 1));
}

/// The outputs the XML info node describes: one `.../outInfo/ID/` node each, with its `info`
/// sub-node (the sensor size) before the next output's node.
std::vector<StreamDescription> ParseStreams(std::string_view xml) {
  constexpr std::string_view kTag = "outInfo/";
  std::vector<std::pair<std::size_t, int>> starts;  // (position, id) of each output's node
  for (std::size_t at = xml.find(kTag); at != std::string_view::npos; at = xml.find(kTag, at + 1)) {
    const std::size_t digits = at + kTag.size();
    std::size_t end = digits;
    while (end < xml.size() && std::isdigit(static_cast<unsigned char>(xml[end])))
      ++end;
    if (end > digits && end - digits < 9 && end + 1 < xml.size() && xml[end] == '/' &&
        xml[end + 1] == '"')
      starts.emplace_back(at, std::atoi(std::string(xml.substr(digits, end - digits)).c_str()));
  }
  std::vector<StreamDescription> out;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const std::size_t begin = starts[i].first;
    const std::size_t end = i + 1 < starts.size() ? starts[i + 1].first : xml.size();
    const std::string_view node = xml.substr(begin, end - begin);
    StreamDescription s;
    s.id = starts[i].second;
    s.type = Attribute(node, "typeIdentifier");
    s.module = Attribute(node, "originalModuleName");
    s.output = Attribute(node, "originalOutputName");
    const std::string w = Attribute(node, "sizeX"), h = Attribute(node, "sizeY");
    s.width = w.empty() ? 0 : std::atoi(w.c_str());
    s.height = h.empty() ? 0 : std::atoi(h.c_str());
    out.push_back(s);
  }
  return out;
}

struct Aedat4File {
  std::string path;
  std::FILE* file = nullptr;
  Compression compression = Compression::kNone;
  StreamDescription stream;
  std::vector<Packet> packets;  // of `stream`, in file order
  std::vector<std::uint8_t> compressed, buffer;

  ~Aedat4File() {
    if (file) std::fclose(file);
  }

  Status Fail(std::int64_t byte, const std::string& what) const {
    return ParseError(
        StrFormat("%s, byte %lld: %s", path.c_str(), static_cast<long long>(byte), what.c_str()));
  }

  /// Header, stream choice (`type` and the user's `wanted`), and the packet index.
  Status Index(const std::string& type, const std::string& wanted) {
    AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "AEDAT4 file"));
    file = std::fopen(path.c_str(), "rb");
    if (!file) return NotFound(path + ": cannot open the AEDAT4 file");
    char magic[kMagic.size()];
    if (std::fread(magic, 1, kMagic.size(), file) != kMagic.size() ||
        std::string_view(magic, kMagic.size()) != kMagic) {
      return InvalidArgument(path +
                             ": not an AEDAT 4.0 file (no '#!AER-DAT4.0' line); AEDAT 2.0 / 3.1 "
                             "files can be converted with DV's Convert module");
    }
    std::int32_t header_size = 0;
    if (std::fread(&header_size, 4, 1, file) != 1 || header_size <= 0 || header_size > (64 << 20))
      return Fail(static_cast<std::int64_t>(kMagic.size()), "no valid IOHeader size");
    std::vector<std::uint8_t> header(static_cast<std::size_t>(header_size));
    if (std::fread(header.data(), 1, header.size(), file) != header.size())
      return Fail(static_cast<std::int64_t>(kMagic.size()) + 4, "the IOHeader is truncated");
    const FlatBuffer fb(header.data(), header.size());
    std::size_t root = 0, info_at = 0, info_first = 0, info_len = 0;
    if (!fb.Root(&root) || !fb.Field(root, 2, &info_at) ||
        !fb.Vector(info_at, 1, &info_first, &info_len)) {
      return Fail(static_cast<std::int64_t>(kMagic.size()) + 4,
                  "the IOHeader has no readable stream description (infoNode)");
    }
    const int compression_code = fb.Scalar<std::int32_t>(root, 0, 0);
    if (compression_code < 0 || compression_code > 4)
      return Fail(static_cast<std::int64_t>(kMagic.size()) + 4,
                  StrFormat("unknown compression %d", compression_code));
    compression = static_cast<Compression>(compression_code);
    const std::int64_t data_table = fb.Scalar<std::int64_t>(root, 1, -1);
    const std::string xml(reinterpret_cast<const char*>(header.data() + info_first), info_len);

    std::vector<StreamDescription> candidates;
    std::string known;
    for (const StreamDescription& s : ParseStreams(xml)) {
      known += StrFormat("%s%d %s (%s/%s)", known.empty() ? "" : ", ", s.id, s.type.c_str(),
                         s.module.c_str(), s.output.c_str());
      if (s.type != type) continue;
      if (wanted.empty() || wanted == std::to_string(s.id) || wanted == s.module ||
          wanted == s.output)
        candidates.push_back(s);
    }
    if (candidates.empty()) {
      return NotFound(StrFormat("%s: no %s stream%s; the file has: %s", path.c_str(), type.c_str(),
                                wanted.empty() ? "" : (" named '" + wanted + "'").c_str(),
                                known.c_str()));
    }
    if (candidates.size() > 1) {
      return InvalidArgument(
          StrFormat("%s: %zu %s streams; name one (its id or DV name) as the "
                    "sequence's topic; the file has: %s",
                    path.c_str(), candidates.size(), type.c_str(), known.c_str()));
    }
    stream = candidates.front();

    // Packet headers up to the data table (or the end of the file).
    std::int64_t at = static_cast<std::int64_t>(kMagic.size()) + 4 + header_size;
    std::fseek(file, 0, SEEK_END);
    const std::int64_t end = data_table >= at ? data_table : std::ftell(file);
    while (at < end) {
      std::int32_t head[2];
      std::fseek(file, static_cast<long>(at), SEEK_SET);
      if (end - at < 8 || std::fread(head, 4, 2, file) != 2)
        return Fail(at, "truncated packet header (the recording was cut short?)");
      if (head[1] <= 0 || head[1] > end - at - 8) {
        return Fail(at, StrFormat("packet of stream %d claims %d bytes, %lld are left", head[0],
                                  head[1], static_cast<long long>(end - at - 8)));
      }
      if (head[0] == stream.id) packets.push_back({at + 8, head[1]});
      at += 8 + head[1];
    }
    return Status::Ok();
  }

  /// Decompresses packet `i` into `buffer`; the size prefix is checked and stripped (the
  /// flatbuffer starts at buffer.data() + 4).
  Status Load(std::size_t i) {
    const Packet& p = packets[i];
    compressed.resize(static_cast<std::size_t>(p.size));
    std::fseek(file, static_cast<long>(p.offset), SEEK_SET);
    if (std::fread(compressed.data(), 1, compressed.size(), file) != compressed.size())
      return Fail(p.offset, "packet truncated");
    switch (compression) {
      case Compression::kNone:
        buffer = compressed;
        break;
      case Compression::kLz4:
      case Compression::kLz4High:
        if (Status s = DecompressLz4Frame(compressed, 0, &buffer); !s.ok())
          return Fail(p.offset, s.message());
        break;
      case Compression::kZstd:
      case Compression::kZstdHigh:
        if (Status s = DecompressZstd(compressed, 0, &buffer); !s.ok())
          return Fail(p.offset, s.message());
        break;
    }
    std::uint32_t prefix = 0;
    if (buffer.size() < 8) return Fail(p.offset, "packet too short for a flatbuffer");
    std::memcpy(&prefix, buffer.data(), 4);
    if (prefix + 4 != buffer.size()) {
      return Fail(p.offset, StrFormat("packet holds %zu bytes, its flatbuffer says %u",
                                      buffer.size() - 4, prefix));
    }
    return Status::Ok();
  }
};

/// The elements vector (field 0 of the root table) of the loaded packet: its first element and
/// length (0 for an empty packet).
Status Elements(const Aedat4File& f, const FlatBuffer& fb, std::int64_t where,
                std::size_t element_size, std::size_t* first, std::size_t* n) {
  std::size_t root = 0, field = 0;
  *n = 0;
  if (!fb.Root(&root)) return f.Fail(where, "packet without a root table");
  if (!fb.Field(root, 0, &field)) return Status::Ok();
  if (!fb.Vector(field, element_size, first, n))
    return f.Fail(where, "element vector out of bounds");
  return Status::Ok();
}

/// The elements of the loaded packet `packet` (index into file->packets), in file order.
Status DecodeEvents(const Aedat4File& f, std::size_t packet, std::vector<events::Event>* out) {
  const std::int64_t where = f.packets[packet].offset;
  const FlatBuffer fb(f.buffer.data() + 4, f.buffer.size() - 4);
  std::size_t first = 0, n = 0;
  AAVIO_RETURN_IF_ERROR(Elements(f, fb, where, 16, &first, &n));
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t t_us = 0;
    std::int16_t x = 0, y = 0;
    std::uint8_t on = 0;
    const std::size_t at = first + 16 * i;
    fb.Read(at, &t_us);
    fb.Read(at + 8, &x);
    fb.Read(at + 10, &y);
    fb.Read(at + 12, &on);
    if (x < 0 || y < 0 || (f.stream.width > 0 && (x >= f.stream.width || y >= f.stream.height))) {
      return f.Fail(where, StrFormat("event %zu of the packet at (%d, %d) is outside the %dx%d "
                                     "sensor the header states",
                                     i, x, y, f.stream.width, f.stream.height));
    }
    if (t_us < 0 || t_us > INT64_MAX / 1000)
      return f.Fail(where, StrFormat("event %zu has an invalid time %lld µs", i,
                                     static_cast<long long>(t_us)));
    events::Event e;
    e.t_ns = t_us * 1000;
    e.x = static_cast<std::uint16_t>(x);
    e.y = static_cast<std::uint16_t>(y);
    e.polarity = on ? 1 : 0;
    out->push_back(e);
  }
  return Status::Ok();
}

Status DecodeImu(const Aedat4File& f, std::size_t packet, std::vector<imu::ImuSample>* out) {
  const std::int64_t where = f.packets[packet].offset;
  const FlatBuffer fb(f.buffer.data() + 4, f.buffer.size() - 4);
  std::size_t first = 0, n = 0;
  AAVIO_RETURN_IF_ERROR(Elements(f, fb, where, 4, &first, &n));
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t table = 0;
    if (!fb.TableAt(first, i, &table))
      return f.Fail(where, StrFormat("IMU sample %zu out of bounds", i));
    const std::int64_t t_us = fb.Scalar<std::int64_t>(table, 0, -1);
    if (t_us < 0 || t_us > INT64_MAX / 1000)
      return f.Fail(where, StrFormat("IMU sample %zu has no valid time", i));
    imu::ImuSample s;
    s.t_ns = t_us * 1000;
    for (int k = 0; k < 3; ++k) {
      s.accel_m_s2[k] =
          static_cast<double>(fb.Scalar<float>(table, 2 + k, 0.0f)) * kStandardGravity;
      s.gyro_rad_s[k] = static_cast<double>(fb.Scalar<float>(table, 5 + k, 0.0f)) * kDegToRad;
    }
    if (!s.accel_m_s2.allFinite() || !s.gyro_rad_s.allFinite())
      return f.Fail(where, StrFormat("IMU sample %zu is not finite", i));
    out->push_back(s);
  }
  return Status::Ok();
}

template <typename T>
using Decoder = Status (*)(const Aedat4File&, std::size_t, std::vector<T>*);

/// One stream of an AEDAT4 file, packet by packet through the reorder window.
template <typename T>
class Aedat4Stream final : public Stream<T> {
 public:
  static Expected<std::unique_ptr<Stream<T>>> Open(const std::string& path, const std::string& type,
                                                   const std::string& wanted,
                                                   const StreamOptions& options,
                                                   Decoder<T> decode) {
    auto s = std::unique_ptr<Aedat4Stream>(new Aedat4Stream(options, decode));
    s->f_.path = path;
    AAVIO_RETURN_IF_ERROR(s->f_.Index(type, wanted));
    s->info_.description =
        "AEDAT4 " + type + " stream " + std::to_string(s->f_.stream.id) + ": " + path;
    s->info_.width = s->f_.stream.width;
    s->info_.height = s->f_.stream.height;
    // One full pass: count, time range, every packet decoded once, and the latest time up to
    // each packet (for Seek).
    std::int64_t count = 0;
    std::vector<T> elements;
    for (std::size_t i = 0; i < s->f_.packets.size(); ++i) {
      elements.clear();
      AAVIO_RETURN_IF_ERROR(s->f_.Load(i));
      AAVIO_RETURN_IF_ERROR(decode(s->f_, i, &elements));
      for (const T& e : elements) {
        if (count == 0 || e.t_ns < s->info_.t_first_ns) s->info_.t_first_ns = e.t_ns;
        if (count == 0 || e.t_ns > s->info_.t_last_ns) s->info_.t_last_ns = e.t_ns;
        ++count;
      }
      s->latest_ns_.push_back(count > 0 ? s->info_.t_last_ns : std::numeric_limits<TimeNs>::min());
    }
    s->info_.count = count;
    return std::unique_ptr<Stream<T>>(std::move(s));
  }

  const StreamInfo& info() const override { return info_; }

  Status ReadUntil(TimeNs t_end_ns, std::vector<T>* out) override {
    while (!reorder_.CanRelease(t_end_ns) && next_ < f_.packets.size()) {
      block_.clear();
      AAVIO_RETURN_IF_ERROR(f_.Load(next_));
      AAVIO_RETURN_IF_ERROR(decode_(f_, next_, &block_));
      const std::string where = StrFormat("%s, packet at byte %lld", f_.path.c_str(),
                                          static_cast<long long>(f_.packets[next_].offset));
      ++next_;
      std::size_t k = reorder_.AppendInOrder(block_);
      for (; k < block_.size(); ++k) {
        AAVIO_RETURN_IF_ERROR(reorder_.Push(block_[k], where));
        k += reorder_.AppendInOrder(std::span<const T>(block_).subspan(k + 1));
      }
    }
    reorder_.Release(t_end_ns, out);
    return Status::Ok();
  }

  Status Seek(TimeNs t_ns) override {
    // Packets whose every element, and every earlier one, is before t_ns are not read again.
    next_ = static_cast<std::size_t>(std::lower_bound(latest_ns_.begin(), latest_ns_.end(), t_ns) -
                                     latest_ns_.begin());
    reorder_.Reset(t_ns);
    return Status::Ok();
  }

  bool AtEnd() const override { return next_ == f_.packets.size() && reorder_.size() == 0; }

 private:
  Aedat4Stream(const StreamOptions& options, Decoder<T> decode)
      : decode_(decode), reorder_(options.max_reorder_ns) {}

  Aedat4File f_;
  StreamInfo info_;
  Decoder<T> decode_;
  ReorderBuffer<T> reorder_;
  std::size_t next_ = 0;
  std::vector<TimeNs> latest_ns_;  // the latest element time up to each packet (non-decreasing)
  std::vector<T> block_;
};

}  // namespace

Expected<std::unique_ptr<EventStream>> OpenAedat4EventStream(const std::string& path,
                                                             const std::string& stream,
                                                             const StreamOptions& options) {
  return Aedat4Stream<events::Event>::Open(path, "EVTS", stream, options, &DecodeEvents);
}

Expected<std::unique_ptr<ImuStream>> OpenAedat4ImuStream(const std::string& path,
                                                         const std::string& stream,
                                                         const StreamOptions& options) {
  return Aedat4Stream<imu::ImuSample>::Open(path, "IMUS", stream, options, &DecodeImu);
}

}  // namespace aavio::io
