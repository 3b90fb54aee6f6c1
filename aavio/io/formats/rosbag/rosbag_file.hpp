#pragma once
/// A reader of the ROS1 bag v2.0 container (docs/io.md) with no ROS installation: the index
/// (connections and chunk infos at the end of the file) and the chunks, uncompressed, bz2 or lz4
/// (LZ4 frame format). Messages stay serialized; rosbag_messages.hpp decodes them.

#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"

namespace aavio::io::rosbag {

struct Connection {
  std::uint32_t id = 0;
  std::string topic;
  std::string type;    ///< e.g. "dvs_msgs/EventArray"
  std::string md5sum;  ///< identifies the layout; several type names share one (docs/io.md)
  std::string message_definition;
};

struct ChunkInfo {
  std::uint64_t position = 0;  ///< file offset of the chunk record
  TimeNs start_ns = 0;         ///< earliest message (bag) time in the chunk
  TimeNs end_ns = 0;           ///< latest message (bag) time in the chunk
  std::map<std::uint32_t, std::uint32_t> message_counts;  ///< per connection id
};

/// One message record of a chunk: serialized bytes valid during the visit.
struct MessageView {
  std::uint32_t connection = 0;
  TimeNs bag_time_ns = 0;
  std::span<const std::uint8_t> data;
};

class BagFile {
 public:
  /// Opens the file and reads its index. A bag that was not closed properly (no index) is refused
  /// with a hint to run `rosbag reindex`.
  static Expected<std::unique_ptr<BagFile>> Open(const std::string& path);
  ~BagFile();

  const std::string& path() const { return path_; }
  const std::vector<Connection>& connections() const { return connections_; }
  const std::vector<ChunkInfo>& chunks() const { return chunks_; }
  std::uint64_t MessageCount(std::uint32_t connection) const;

  /// Decompresses chunk `index` and calls `visit` for each message record in it, in file order.
  Status ReadChunk(std::size_t index, const std::function<Status(const MessageView&)>& visit);

 private:
  BagFile() = default;
  Status Fail(const std::string& what) const;
  Status ReadAt(std::uint64_t offset, void* buffer, std::size_t n, const char* what);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t file_size_ = 0;
  std::vector<Connection> connections_;
  std::vector<ChunkInfo> chunks_;
  std::vector<std::uint8_t> compressed_;
  std::vector<std::uint8_t> chunk_;
};

}  // namespace aavio::io::rosbag
