#include "aavio/io/formats/ros2_bag/mcap_file.hpp"

#include <algorithm>
#include <cstring>

#include "aavio/common/format.hpp"
#include "aavio/io/decompression.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::io {

namespace {

constexpr unsigned char kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
enum Opcode : std::uint8_t {
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kDataEnd = 0x0F,
};
constexpr std::uint64_t kMaxRecord = std::uint64_t{1} << 32;  // 4 GiB: anything larger is corrupt

/// Little-endian fields of one record's content, bounds-checked.
class Fields {
 public:
  Fields(const unsigned char* p, std::uint64_t n) : p_(p), n_(n) {}
  template <typename T>
  bool Int(T* v) {
    if (n_ - at_ < sizeof(T)) return false;
    std::memcpy(v, p_ + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool String(std::string* s) {
    std::uint32_t len = 0;
    if (!Int(&len) || n_ - at_ < len) return false;
    s->assign(reinterpret_cast<const char*>(p_ + at_), len);
    at_ += len;
    return true;
  }
  bool Skip(std::uint64_t len) {
    if (n_ - at_ < len) return false;
    at_ += len;
    return true;
  }
  const unsigned char* here() const { return p_ + at_; }
  std::uint64_t left() const { return n_ - at_; }

 private:
  const unsigned char* p_;
  std::uint64_t n_, at_ = 0;
};

}  // namespace

McapReader::~McapReader() {
  if (file_) std::fclose(file_);
}

Status McapReader::Fail(std::int64_t at, const std::string& what) const {
  return ParseError(
      StrFormat("%s, byte %lld: %s", path_.c_str(), static_cast<long long>(at), what.c_str()));
}

Expected<std::unique_ptr<McapReader>> McapReader::Open(const std::string& path) {
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "MCAP file"));
  auto r = std::unique_ptr<McapReader>(new McapReader());
  r->path_ = path;
  r->file_ = std::fopen(path.c_str(), "rb");
  if (!r->file_) return NotFound(path + ": cannot open the MCAP file");
  unsigned char magic[8];
  if (std::fread(magic, 1, 8, r->file_) != 8 || std::memcmp(magic, kMagic, 8) != 0)
    return InvalidArgument(path + ": not an MCAP file (no '\\x89MCAP0' magic)");
  std::fseek(r->file_, 0, SEEK_END);
  r->file_size_ = std::ftell(r->file_);
  // One pass for the channels; every record and chunk is checked on the way.
  r->Rewind();
  Message m;
  while (true) {
    Expected<bool> more = r->Next(&m);
    if (!more) return more.status();
    if (!*more) break;
  }
  r->Rewind();
  return r;
}

void McapReader::Rewind() {
  pos_ = 8;
  ended_ = false;
  chunk_.clear();
  chunk_pos_ = 0;
}

Expected<bool> McapReader::Record(std::uint8_t opcode, const unsigned char* content,
                                  std::uint64_t length, std::int64_t at, Message* message) {
  Fields f(content, length);
  switch (opcode) {
    case kSchema: {
      std::uint16_t id = 0;
      std::string name;
      if (!f.Int(&id) || !f.String(&name)) return Fail(at, "truncated Schema record");
      if (std::none_of(schemas_.begin(), schemas_.end(),
                       [&](const auto& s) { return s.first == id; }))
        schemas_.emplace_back(id, name);
      return false;
    }
    case kChannel: {
      Channel c;
      std::uint16_t schema = 0;
      if (!f.Int(&c.id) || !f.Int(&schema) || !f.String(&c.topic) || !f.String(&c.message_encoding))
        return Fail(at, "truncated Channel record");
      for (const auto& [id, name] : schemas_)
        if (id == schema) c.schema_name = name;
      if (std::none_of(channels_.begin(), channels_.end(),
                       [&](const Channel& o) { return o.id == c.id; }))
        channels_.push_back(c);
      return false;
    }
    case kMessage: {
      std::uint32_t sequence = 0;
      std::uint64_t publish_time = 0;
      if (!f.Int(&message->channel) || !f.Int(&sequence) || !f.Int(&message->log_time_ns) ||
          !f.Int(&publish_time))
        return Fail(at, "truncated Message record");
      message->data = f.here();
      message->size = static_cast<std::size_t>(f.left());
      message->offset = at;
      return true;
    }
    default:
      return false;  // indexes, attachments, metadata, statistics: not needed to read messages
  }
}

Status McapReader::ReadChunk(std::int64_t at, std::uint64_t length) {
  Fields f(record_.data(), length);
  std::uint64_t start = 0, end = 0, size = 0, records = 0;
  std::uint32_t crc = 0;
  std::string compression;
  if (!f.Int(&start) || !f.Int(&end) || !f.Int(&size) || !f.Int(&crc) || !f.String(&compression) ||
      !f.Int(&records) || f.left() < records)
    return Fail(at, "truncated Chunk record");
  if (size > kMaxRecord) return Fail(at, "a chunk larger than 4 GiB: a corrupt file");
  if (compression.empty() && records != size) {
    return Fail(at, "an uncompressed chunk whose sizes disagree");
  }
  if (compression.empty()) {
    chunk_.resize(static_cast<std::size_t>(size));
    // An empty chunk has nothing to copy (and memcpy must not see its null data()).
    if (size > 0) std::memcpy(chunk_.data(), f.here(), static_cast<std::size_t>(size));
  } else if (compression == "lz4" || compression == "zstd") {
    const std::span<const unsigned char> packed(f.here(), static_cast<std::size_t>(records));
    const auto stated = static_cast<std::size_t>(size);
    const Status s = compression == "lz4" ? DecompressLz4Frame(packed, stated, &chunk_)
                                          : DecompressZstd(packed, stated, &chunk_);
    if (!s.ok()) return Fail(at, compression + " chunk: " + s.message());
  } else {
    return Fail(at, "chunk compression '" + compression + "' is not read (lz4, zstd or none)");
  }
  chunk_pos_ = 0;
  chunk_at_ = at;
  return Status::Ok();
}

Expected<bool> McapReader::Next(Message* message) {
  while (true) {
    // Records inside the current chunk first.
    while (chunk_pos_ < chunk_.size()) {
      Fields f(chunk_.data() + chunk_pos_, chunk_.size() - chunk_pos_);
      std::uint8_t opcode = 0;
      std::uint64_t length = 0;
      if (!f.Int(&opcode) || !f.Int(&length) || f.left() < length)
        return Fail(chunk_at_, "a truncated record inside the chunk");
      const unsigned char* content = f.here();
      chunk_pos_ += 9 + static_cast<std::size_t>(length);
      Expected<bool> is_message = Record(opcode, content, length, chunk_at_, message);
      if (!is_message) return is_message.status();
      if (*is_message) return true;
    }
    if (ended_ || pos_ >= file_size_) return false;
    unsigned char head[9];
    std::fseek(file_, static_cast<long>(pos_), SEEK_SET);
    if (file_size_ - pos_ < 9 || std::fread(head, 1, 9, file_) != 9)
      return Fail(pos_, "truncated record header (the recording was cut short?)");
    const std::uint8_t opcode = head[0];
    std::uint64_t length = 0;
    std::memcpy(&length, head + 1, 8);
    const std::int64_t at = pos_;
    if (length > static_cast<std::uint64_t>(file_size_ - pos_ - 9)) {
      return Fail(at, StrFormat("record 0x%02X claims %llu bytes, %lld are left", opcode,
                                static_cast<unsigned long long>(length),
                                static_cast<long long>(file_size_ - pos_ - 9)));
    }
    pos_ += 9 + static_cast<std::int64_t>(length);
    if (opcode == kDataEnd || opcode == kFooter) {
      ended_ = true;
      return false;
    }
    if (opcode != kSchema && opcode != kChannel && opcode != kMessage && opcode != kChunk)
      continue;  // skipped without reading
    record_.resize(static_cast<std::size_t>(length));
    if (std::fread(record_.data(), 1, record_.size(), file_) != record_.size())
      return Fail(at, "record truncated");
    if (opcode == kChunk) {
      AAVIO_RETURN_IF_ERROR(ReadChunk(at, length));
      continue;
    }
    Expected<bool> is_message = Record(opcode, record_.data(), length, at, message);
    if (!is_message) return is_message.status();
    if (*is_message) return true;
  }
}

}  // namespace aavio::io
