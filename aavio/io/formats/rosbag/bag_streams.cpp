#include "aavio/io/formats/rosbag/bag_streams.hpp"

#include <algorithm>
#include <set>

#include "aavio/io/decoded_stream_impl.hpp"
#include "aavio/io/formats/rosbag/rosbag_messages.hpp"

namespace aavio::io {

std::string DescribeBagTopics(const rosbag::BagFile& bag) {
  std::map<std::string, std::pair<std::string, std::uint64_t>> topics;
  for (const rosbag::Connection& c : bag.connections()) {
    auto& entry = topics[c.topic];
    entry.first = c.type;
    entry.second += bag.MessageCount(c.id);
  }
  std::string text;
  for (const auto& [topic, info] : topics) {
    text += (text.empty() ? "" : ", ") + topic + " (" + info.first + ", " +
            std::to_string(info.second) + " msgs)";
  }
  return text.empty() ? "none" : text;
}

Expected<std::string> FindTopicByType(const rosbag::BagFile& bag, const char* md5,
                                      const char* type_name) {
  std::set<std::string> topics;
  for (const rosbag::Connection& c : bag.connections()) {
    if (c.md5sum == md5) topics.insert(c.topic);
  }
  if (topics.size() == 1) return *topics.begin();
  if (topics.empty()) {
    return NotFound(bag.path() + ": no " + type_name + " topic; topics: " + DescribeBagTopics(bag));
  }
  std::string list;
  for (const std::string& t : topics)
    list += (list.empty() ? "" : ", ") + t;
  return InvalidArgument(bag.path() + ": several " + type_name + " topics (" + list +
                         "); name the one to use");
}

namespace {

/// The connections of `topic`, checked against the expected message layout.
Expected<std::set<std::uint32_t>> TopicConnections(const rosbag::BagFile& bag,
                                                   const std::string& topic,
                                                   const rosbag::MessageType& expected,
                                                   const char* what) {
  std::set<std::uint32_t> ids;
  for (const rosbag::Connection& c : bag.connections()) {
    if (c.topic != topic) continue;
    if (c.md5sum == rosbag::kLegacyEventArrayMd5) {
      return InvalidArgument(bag.path() + ": topic " + topic +
                             " uses the pre-2017 dvs_msgs/EventArray layout (uint64 time), which "
                             "aavio does not read; re-record or convert it to the current layout");
    }
    if (c.md5sum != expected.md5sum) {
      return InvalidArgument(bag.path() + ": topic " + topic + " has type " + c.type + " (md5 " +
                             c.md5sum + "), not " + what + " (" + expected.name + " layout, md5 " +
                             expected.md5sum + ")");
    }
    ids.insert(c.id);
  }
  if (ids.empty()) {
    return NotFound(bag.path() + ": no topic '" + topic + "'; topics: " + DescribeBagTopics(bag));
  }
  return ids;
}

/// What the event and IMU bag streams share: the chunks holding the topic, decoded one by one.
template <typename T>
struct BagStreamCore {
  std::unique_ptr<rosbag::BagFile> bag;
  std::string topic;
  std::set<std::uint32_t> connections;
  std::vector<std::size_t> chunks;  // indices of the chunks holding the topic, in file order
  std::size_t next_chunk = 0;
  ReorderBuffer<T> reorder{0};
  StreamInfo info;
  TimeNs max_reorder_ns = 0;
  StreamOptions options;
  std::uint64_t messages = 0;
  std::vector<T> scratch;

  // Decodes one message into `out`; returns a non-ok status for a malformed message.
  std::function<Status(const rosbag::MessageView&, std::vector<T>*)> decode;

  Status Init(std::unique_ptr<rosbag::BagFile> b, const std::string& t, std::set<std::uint32_t> ids,
              const StreamOptions& o) {
    bag = std::move(b);
    topic = t;
    connections = std::move(ids);
    options = o;
    max_reorder_ns = o.max_reorder_ns;
    reorder = ReorderBuffer<T>(o.max_reorder_ns);
    const auto& all = bag->chunks();
    for (std::size_t i = 0; i < all.size(); ++i) {
      for (std::uint32_t id : connections) {
        auto it = all[i].message_counts.find(id);
        if (it != all[i].message_counts.end() && it->second > 0) {
          chunks.push_back(i);
          break;
        }
      }
    }
    for (std::uint32_t id : connections)
      messages += bag->MessageCount(id);
    info.count = -1;
    // First and last stamps from the first and last chunk of the topic.
    if (!chunks.empty()) {
      for (std::size_t which : {chunks.front(), chunks.back()}) {
        std::vector<T> elements;
        AAVIO_RETURN_IF_ERROR(DecodeChunk(which, &elements));
        if (elements.empty()) continue;
        auto [lo, hi] = std::minmax_element(elements.begin(), elements.end(),
                                            [](const T& l, const T& r) { return l.t_ns < r.t_ns; });
        if (which == chunks.front()) info.t_first_ns = lo->t_ns;
        if (which == chunks.back()) info.t_last_ns = hi->t_ns;
      }
    }
    return Status::Ok();
  }

  Status DecodeChunk(std::size_t chunk, std::vector<T>* out) {
    return bag->ReadChunk(chunk, [&](const rosbag::MessageView& m) -> Status {
      if (!connections.count(m.connection)) return Status::Ok();
      return decode(m, out);
    });
  }

  Status Fill(TimeNs t_end_ns) {
    while (!reorder.CanRelease(t_end_ns) && next_chunk < chunks.size()) {
      scratch.clear();
      AAVIO_RETURN_IF_ERROR(DecodeChunk(chunks[next_chunk], &scratch));
      const std::string where =
          bag->path() + ": topic " + topic + ", chunk " + std::to_string(chunks[next_chunk]);
      for (const T& element : scratch)
        AAVIO_RETURN_IF_ERROR(reorder.Push(element, where));
      ++next_chunk;
    }
    return Status::Ok();
  }

  Status ReadUntil(TimeNs t_end_ns, std::vector<T>* out) {
    AAVIO_RETURN_IF_ERROR(Fill(t_end_ns));
    reorder.Release(t_end_ns, out);
    return Status::Ok();
  }

  Status Seek(TimeNs t_ns) {
    // Bag (receive) times are at or after the data's own stamps: chunks that end before
    // t − window hold nothing at or after t.
    next_chunk = 0;
    const auto& all = bag->chunks();
    while (next_chunk < chunks.size() && all[chunks[next_chunk]].end_ns < t_ns - max_reorder_ns) {
      ++next_chunk;
    }
    reorder.Reset(t_ns);
    return Status::Ok();
  }

  bool AtEnd() const { return next_chunk >= chunks.size() && reorder.size() == 0; }
};

}  // namespace

struct BagEventDecoder : BagStreamCore<events::Event> {};
template class DecodedStream<events::Event, BagEventDecoder>;

struct BagImuDecoder : BagStreamCore<imu::ImuSample> {};
template class DecodedStream<imu::ImuSample, BagImuDecoder>;

BagEventStream::~BagEventStream() = default;

Expected<std::unique_ptr<BagEventStream>> BagEventStream::Open(const std::string& path,
                                                               const std::string& topic,
                                                               const StreamOptions& options) {
  Expected<std::unique_ptr<rosbag::BagFile>> bag = rosbag::BagFile::Open(path);
  if (!bag) return bag.status();
  Expected<std::set<std::uint32_t>> ids =
      TopicConnections(**bag, topic, rosbag::kEventArray, "an event array");
  if (!ids) return ids.status();
  auto s = std::make_unique<BagEventDecoder>();
  BagEventDecoder* raw = s.get();
  s->decode = [raw](const rosbag::MessageView& m, std::vector<events::Event>* out) -> Status {
    rosbag::EventArrayHeader header;
    const std::size_t before = out->size();
    if (!rosbag::DecodeEventArray(m.data, &header, out)) {
      return ParseError(raw->bag->path() + ": topic " + raw->topic +
                        ": malformed EventArray message at bag time " +
                        FormatSecondsNs(m.bag_time_ns) + " s");
    }
    if (raw->info.width == 0) {
      raw->info.width = static_cast<int>(header.width);
      raw->info.height = static_cast<int>(header.height);
    }
    const int width = raw->options.width > 0 ? raw->options.width : static_cast<int>(header.width);
    const int height =
        raw->options.width > 0 ? raw->options.height : static_cast<int>(header.height);
    if (width > 0 && height > 0) {
      for (std::size_t i = before; i < out->size(); ++i) {
        const events::Event& e = (*out)[i];
        if (e.x >= width || e.y >= height) {
          return InvalidArgument(raw->bag->path() + ": topic " + raw->topic + ": event at (" +
                                 std::to_string(e.x) + ", " + std::to_string(e.y) + ") at " +
                                 FormatSecondsNs(e.t_ns) + " s is outside the " +
                                 std::to_string(width) + "x" + std::to_string(height) + " sensor");
        }
      }
    }
    return Status::Ok();
  };
  AAVIO_RETURN_IF_ERROR(s->Init(std::move(*bag), topic, std::move(*ids), options));
  s->info.description = "bag events: " + path + " " + topic;
  return std::unique_ptr<BagEventStream>(new BagEventStream(std::move(s)));
}

std::uint64_t BagEventStream::message_count() const {
  return decoder_->messages;
}

BagImuStream::~BagImuStream() = default;

Expected<std::unique_ptr<BagImuStream>> BagImuStream::Open(const std::string& path,
                                                           const std::string& topic_or_empty,
                                                           const StreamOptions& options) {
  Expected<std::unique_ptr<rosbag::BagFile>> bag = rosbag::BagFile::Open(path);
  if (!bag) return bag.status();
  std::string topic = topic_or_empty;
  if (topic.empty()) {
    Expected<std::string> found = FindTopicByType(**bag, rosbag::kImu.md5sum, "sensor_msgs/Imu");
    if (!found) return found.status();
    topic = *found;
  }
  Expected<std::set<std::uint32_t>> ids = TopicConnections(**bag, topic, rosbag::kImu, "an IMU");
  if (!ids) return ids.status();
  auto s = std::make_unique<BagImuDecoder>();
  BagImuDecoder* raw = s.get();
  s->decode = [raw](const rosbag::MessageView& m, std::vector<imu::ImuSample>* out) -> Status {
    imu::ImuSample sample;
    if (!rosbag::DecodeImu(m.data, &sample)) {
      return ParseError(raw->bag->path() + ": topic " + raw->topic +
                        ": malformed Imu message at bag time " + FormatSecondsNs(m.bag_time_ns) +
                        " s");
    }
    out->push_back(sample);
    return Status::Ok();
  };
  AAVIO_RETURN_IF_ERROR(s->Init(std::move(*bag), topic, std::move(*ids), options));
  s->info.count = static_cast<std::int64_t>(s->messages);
  s->info.description = "bag IMU: " + path + " " + topic;
  return std::unique_ptr<BagImuStream>(new BagImuStream(std::move(s)));
}

Expected<std::vector<geometry::StampedPose>> ReadBagPoses(const std::string& path,
                                                          const std::string& topic_or_empty) {
  Expected<std::unique_ptr<rosbag::BagFile>> bag = rosbag::BagFile::Open(path);
  if (!bag) return bag.status();
  std::string topic = topic_or_empty;
  if (topic.empty()) {
    Expected<std::string> found =
        FindTopicByType(**bag, rosbag::kPoseStamped.md5sum, "geometry_msgs/PoseStamped");
    if (!found) return found.status();
    topic = *found;
  }
  Expected<std::set<std::uint32_t>> ids =
      TopicConnections(**bag, topic, rosbag::kPoseStamped, "a pose");
  if (!ids) return ids.status();
  std::vector<geometry::StampedPose> poses;
  for (std::size_t i = 0; i < (*bag)->chunks().size(); ++i) {
    AAVIO_RETURN_IF_ERROR((*bag)->ReadChunk(i, [&](const rosbag::MessageView& m) -> Status {
      if (!ids->count(m.connection)) return Status::Ok();
      geometry::StampedPose pose;
      if (!rosbag::DecodePoseStamped(m.data, &pose)) {
        return ParseError(path + ": topic " + topic + ": malformed PoseStamped message");
      }
      poses.push_back(pose);
      return Status::Ok();
    }));
  }
  std::stable_sort(poses.begin(), poses.end(),
                   [](const auto& a, const auto& b) { return a.t_ns < b.t_ns; });
  return poses;
}

}  // namespace aavio::io
