#include "aavio/io/formats/rosbag/rosbag_file.hpp"

#include <bzlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "aavio/io/decompression.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::io::rosbag {

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
constexpr std::uint8_t kOpMessage = 0x02, kOpBagHeader = 0x03, kOpChunk = 0x05, kOpChunkInfo = 0x06,
                       kOpConnection = 0x07;

std::uint32_t U32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
std::uint64_t U64(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}
TimeNs Time(const std::uint8_t* p) {
  return static_cast<TimeNs>(U32(p)) * kNsPerS + static_cast<TimeNs>(U32(p + 4));
}

/// The fields of a record header ("name=value" entries with u32 lengths).
class Header {
 public:
  bool Parse(std::span<const std::uint8_t> bytes) {
    std::size_t i = 0;
    while (i < bytes.size()) {
      if (bytes.size() - i < 4) return false;
      const std::uint32_t len = U32(bytes.data() + i);
      i += 4;
      if (len > bytes.size() - i) return false;
      const std::string_view field(reinterpret_cast<const char*>(bytes.data() + i), len);
      const std::size_t eq = field.find('=');
      if (eq == std::string_view::npos) return false;
      fields_[std::string(field.substr(0, eq))] = field.substr(eq + 1);
      i += len;
    }
    return true;
  }
  const std::string_view* Find(const char* name) const {
    auto it = fields_.find(name);
    return it == fields_.end() ? nullptr : &it->second;
  }
  bool Op(std::uint8_t* op) const {
    const std::string_view* v = Find("op");
    if (!v || v->size() != 1) return false;
    *op = static_cast<std::uint8_t>((*v)[0]);
    return true;
  }
  bool U32Field(const char* name, std::uint32_t* out) const {
    const std::string_view* v = Find(name);
    if (!v || v->size() != 4) return false;
    *out = U32(reinterpret_cast<const std::uint8_t*>(v->data()));
    return true;
  }
  bool U64Field(const char* name, std::uint64_t* out) const {
    const std::string_view* v = Find(name);
    if (!v || v->size() != 8) return false;
    *out = U64(reinterpret_cast<const std::uint8_t*>(v->data()));
    return true;
  }
  bool TimeField(const char* name, TimeNs* out) const {
    const std::string_view* v = Find(name);
    if (!v || v->size() != 8) return false;
    *out = Time(reinterpret_cast<const std::uint8_t*>(v->data()));
    return true;
  }
  std::string String(const char* name) const {
    const std::string_view* v = Find(name);
    return v ? std::string(*v) : std::string();
  }

 private:
  std::map<std::string, std::string_view, std::less<>> fields_;
};

/// A record inside a memory buffer: header and data spans; advances `offset`.
bool NextRecord(std::span<const std::uint8_t> buffer, std::size_t* offset,
                std::span<const std::uint8_t>* header, std::span<const std::uint8_t>* data) {
  const std::size_t i = *offset;
  if (buffer.size() - i < 4) return false;
  const std::uint32_t header_len = U32(buffer.data() + i);
  if (header_len > buffer.size() - i - 4 || buffer.size() - i - 4 - header_len < 4) return false;
  *header = buffer.subspan(i + 4, header_len);
  const std::uint32_t data_len = U32(buffer.data() + i + 4 + header_len);
  const std::size_t data_at = i + 8 + header_len;
  if (data_len > buffer.size() - data_at) return false;
  *data = buffer.subspan(data_at, data_len);
  *offset = data_at + data_len;
  return true;
}

}  // namespace

BagFile::~BagFile() {
  if (file_) std::fclose(file_);
}

Status BagFile::Fail(const std::string& what) const {
  return ParseError(path_ + ": " + what + "; the bag is truncated or corrupt");
}

Status BagFile::ReadAt(std::uint64_t offset, void* buffer, std::size_t n, const char* what) {
  if (offset + n > file_size_) return Fail(std::string(what) + " extends past the end of the file");
  if (fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0 ||
      std::fread(buffer, 1, n, file_) != n) {
    return IoError(path_ + ": reading " + what + " failed");
  }
  return Status::Ok();
}

std::uint64_t BagFile::MessageCount(std::uint32_t connection) const {
  std::uint64_t count = 0;
  for (const ChunkInfo& c : chunks_) {
    auto it = c.message_counts.find(connection);
    if (it != c.message_counts.end()) count += it->second;
  }
  return count;
}

Expected<std::unique_ptr<BagFile>> BagFile::Open(const std::string& path) {
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "ROS bag"));
  std::error_code ec;
  std::unique_ptr<BagFile> bag(new BagFile());
  bag->path_ = path;
  bag->file_size_ = std::filesystem::file_size(path, ec);
  bag->file_ = std::fopen(path.c_str(), "rb");
  if (!bag->file_) return IoError(path + ": cannot open");

  char magic[kMagicSize] = {0};
  if (bag->file_size_ < kMagicSize || std::fread(magic, 1, kMagicSize, bag->file_) != kMagicSize ||
      std::memcmp(magic, kMagic, kMagicSize) != 0) {
    if (std::memcmp(magic, "#ROSBAG V1.2", 12) == 0) {
      return ParseError(path + ": a ROS bag of format 1.2; convert it with `rosbag fix` first");
    }
    return ParseError(path + ": not a ROS1 bag (no '#ROSBAG V2.0' line at the start)");
  }

  // The bag header record: where the index starts.
  std::uint8_t lengths[4];
  AAVIO_RETURN_IF_ERROR(bag->ReadAt(kMagicSize, lengths, 4, "the bag header"));
  const std::uint32_t header_len = U32(lengths);
  if (header_len > 4096) return bag->Fail("the bag header record is malformed");
  std::vector<std::uint8_t> header_bytes(header_len);
  AAVIO_RETURN_IF_ERROR(
      bag->ReadAt(kMagicSize + 4, header_bytes.data(), header_len, "the bag header"));
  Header header;
  std::uint8_t op = 0;
  std::uint64_t index_pos = 0;
  std::uint32_t conn_count = 0, chunk_count = 0;
  if (!header.Parse(header_bytes) || !header.Op(&op) || op != kOpBagHeader ||
      !header.U64Field("index_pos", &index_pos) || !header.U32Field("conn_count", &conn_count) ||
      !header.U32Field("chunk_count", &chunk_count)) {
    return bag->Fail("the bag header record is malformed");
  }
  if (index_pos == 0) {
    return ParseError(path +
                      ": the bag has no index (recording not closed properly); run "
                      "`rosbag reindex` on it");
  }
  if (index_pos >= bag->file_size_) {
    return ParseError(path + ": the index at byte " + std::to_string(index_pos) +
                      " lies past the end of the file (" + std::to_string(bag->file_size_) +
                      " bytes): the bag is truncated; `rosbag reindex` may recover it");
  }

  // The index section: connection records, then chunk info records.
  std::vector<std::uint8_t> index(bag->file_size_ - index_pos);
  AAVIO_RETURN_IF_ERROR(bag->ReadAt(index_pos, index.data(), index.size(), "the index"));
  std::size_t offset = 0;
  std::span<const std::uint8_t> rec_header, rec_data;
  while (offset < index.size()) {
    if (!NextRecord(index, &offset, &rec_header, &rec_data))
      return bag->Fail("the index is cut short");
    Header h;
    if (!h.Parse(rec_header) || !h.Op(&op)) return bag->Fail("an index record is malformed");
    if (op == kOpConnection) {
      Connection c;
      Header fields;
      if (!h.U32Field("conn", &c.id) || !fields.Parse(rec_data)) {
        return bag->Fail("a connection record is malformed");
      }
      c.topic = h.String("topic");
      c.type = fields.String("type");
      c.md5sum = fields.String("md5sum");
      c.message_definition = fields.String("message_definition");
      bag->connections_.push_back(std::move(c));
    } else if (op == kOpChunkInfo) {
      ChunkInfo info;
      std::uint32_t version = 0, count = 0;
      if (!h.U32Field("ver", &version) || version != 1 ||
          !h.U64Field("chunk_pos", &info.position) || !h.TimeField("start_time", &info.start_ns) ||
          !h.TimeField("end_time", &info.end_ns) || !h.U32Field("count", &count) ||
          rec_data.size() != 8ull * count) {
        return bag->Fail("a chunk info record is malformed");
      }
      for (std::uint32_t k = 0; k < count; ++k) {
        info.message_counts[U32(rec_data.data() + 8 * k)] = U32(rec_data.data() + 8 * k + 4);
      }
      if (info.position >= index_pos) return bag->Fail("a chunk lies inside the index");
      bag->chunks_.push_back(std::move(info));
    }
  }
  if (bag->connections_.size() != conn_count || bag->chunks_.size() != chunk_count) {
    return bag->Fail("the index lists " + std::to_string(bag->connections_.size()) +
                     " connections and " + std::to_string(bag->chunks_.size()) +
                     " chunks but the header announces " + std::to_string(conn_count) + " and " +
                     std::to_string(chunk_count));
  }
  std::sort(bag->chunks_.begin(), bag->chunks_.end(),
            [](const ChunkInfo& a, const ChunkInfo& b) { return a.position < b.position; });
  return bag;
}

Status BagFile::ReadChunk(std::size_t index,
                          const std::function<Status(const MessageView&)>& visit) {
  const ChunkInfo& info = chunks_.at(index);
  const std::string where =
      "chunk " + std::to_string(index) + " at byte " + std::to_string(info.position);
  std::uint8_t len_bytes[4];
  AAVIO_RETURN_IF_ERROR(ReadAt(info.position, len_bytes, 4, where.c_str()));
  const std::uint32_t header_len = U32(len_bytes);
  if (header_len > 1 << 16) return Fail(where + ": malformed record");
  std::vector<std::uint8_t> header_bytes(header_len + 4);
  AAVIO_RETURN_IF_ERROR(
      ReadAt(info.position + 4, header_bytes.data(), header_len + 4, where.c_str()));
  Header h;
  std::uint8_t op = 0;
  std::uint32_t size = 0;
  if (!h.Parse(std::span(header_bytes).first(header_len)) || !h.Op(&op) || op != kOpChunk ||
      !h.U32Field("size", &size)) {
    return Fail(where + ": not a chunk record");
  }
  const std::uint32_t data_len = U32(header_bytes.data() + header_len);
  const std::string compression = h.String("compression");
  const std::uint64_t data_at = info.position + 8 + header_len;
  if (size > (1u << 30)) return Fail(where + ": implausible chunk size " + std::to_string(size));

  // Sizes are checked before anything is allocated for them.
  if (data_at + data_len > file_size_)
    return Fail(where + ": chunk data run past the end of the file");
  if (compression == "none") {
    if (data_len != size) return Fail(where + ": uncompressed chunk of the wrong size");
    chunk_.resize(size);
    AAVIO_RETURN_IF_ERROR(ReadAt(data_at, chunk_.data(), size, where.c_str()));
  } else {
    compressed_.resize(data_len);
    AAVIO_RETURN_IF_ERROR(ReadAt(data_at, compressed_.data(), data_len, where.c_str()));
    if (compression == "bz2") {
      chunk_.resize(size);
      unsigned int out_len = size;
      const int rc =
          BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(chunk_.data()), &out_len,
                                     reinterpret_cast<char*>(compressed_.data()), data_len, 0, 0);
      if (rc != BZ_OK || out_len != size) return Fail(where + ": bz2 data do not decompress");
    } else if (compression == "lz4") {
      if (Status s = DecompressLz4Frame(compressed_, size, &chunk_); !s.ok())
        return Fail(where + ": " + s.message());
    } else {
      return ParseError(path_ + ": " + where + " uses compression '" + compression +
                        "'; aavio reads none, bz2 and lz4");
    }
  }

  std::size_t offset = 0;
  std::span<const std::uint8_t> rec_header, rec_data;
  while (offset < chunk_.size()) {
    if (!NextRecord(chunk_, &offset, &rec_header, &rec_data))
      return Fail(where + ": record cut short");
    Header rh;
    if (!rh.Parse(rec_header) || !rh.Op(&op)) return Fail(where + ": malformed record header");
    if (op != kOpMessage) continue;  // connection records repeat the index
    MessageView m;
    if (!rh.U32Field("conn", &m.connection) || !rh.TimeField("time", &m.bag_time_ns)) {
      return Fail(where + ": malformed message record");
    }
    m.data = rec_data;
    AAVIO_RETURN_IF_ERROR(visit(m));
  }
  return Status::Ok();
}

}  // namespace aavio::io::rosbag
