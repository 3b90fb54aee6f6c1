#pragma once
/// MCAP files (mcap.dev specification, version 0), the storage of ROS 2 bags since Iron: the
/// magic `\x89MCAP0\r\n`, then records — opcode (1 byte), length (uint64), content — of which
/// this reads Schema (0x03), Channel (0x04), Message (0x05) and Chunk (0x06: records compressed
/// with lz4, zstd or not at all), up to DataEnd (0x0F) or the Footer; index and summary records
/// are skipped. Messages come in file order (the order recorders write them, by log time).

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::io {

class McapReader {
 public:
  struct Channel {
    std::uint16_t id = 0;
    std::string topic, message_encoding;
    std::string schema_name;  ///< e.g. "event_camera_msgs/msg/EventPacket"; "" if schemaless
  };
  struct Message {
    std::uint16_t channel = 0;
    std::uint64_t log_time_ns = 0;
    const unsigned char* data = nullptr;  ///< valid until the next call of Next
    std::size_t size = 0;
    std::int64_t offset = 0;  ///< of its record in the file, or of its chunk (for messages)
  };

  /// Opens the file and reads it once for its channels (a corrupt record fails here).
  static Expected<std::unique_ptr<McapReader>> Open(const std::string& path);
  ~McapReader();

  const std::vector<Channel>& channels() const { return channels_; }
  const std::string& path() const { return path_; }
  /// Back to the first record.
  void Rewind();
  /// The next message of any channel; false at the end of the data.
  Expected<bool> Next(Message* message);

 private:
  McapReader() = default;
  Status Fail(std::int64_t at, const std::string& what) const;
  Status ReadChunk(std::int64_t at, std::uint64_t length);
  /// Schema and Channel records are remembered; true for a message.
  Expected<bool> Record(std::uint8_t opcode, const unsigned char* content, std::uint64_t length,
                        std::int64_t at, Message* message);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::int64_t file_size_ = 0, pos_ = 0;
  bool ended_ = false;
  std::vector<unsigned char> record_, chunk_;
  std::size_t chunk_pos_ = 0;
  std::int64_t chunk_at_ = 0;
  std::vector<std::pair<std::uint16_t, std::string>> schemas_;  // id, name
  std::vector<Channel> channels_;
};

}  // namespace aavio::io
