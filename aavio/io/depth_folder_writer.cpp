#include "aavio/io/depth_folder_writer.hpp"

#include <cerrno>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/output_folder.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxQueued = 2;  // maps waiting to be written

// A failed image: an error saying why, and no partial file left.
Status Failed(const std::string& png) {
  Status failed = IoError(CannotWrite(png));
  std::error_code ec;
  fs::remove(png, ec);
  return failed;
}

struct DepthImages {
  TimeNs t_ns = 0;
  std::string index;
  cv::Mat disparity, picture;
};

// Both images of a map, or neither (the index lists pairs written whole).
Status WriteImages(const std::string& dir, const DepthImages& m) {
  const std::string disparity_png = (fs::path(dir) / ("disparity_" + m.index + ".png")).string();
  errno = 0;  // so that a failure's reason is the encoder's
  if (!cv::imwrite(disparity_png, m.disparity)) return Failed(disparity_png);
  if (m.picture.empty()) return Status::Ok();
  const std::string picture_png = (fs::path(dir) / ("inverse_depth_" + m.index + ".png")).string();
  if (!cv::imwrite(picture_png, m.picture)) {
    const Status failed = Failed(picture_png);
    std::error_code ec;
    fs::remove(disparity_png, ec);
    return failed;
  }
  return Status::Ok();
}

}  // namespace

struct DepthFolderWriter::Queue {
  explicit Queue(std::string folder) : dir(std::move(folder)), thread([this] { Run(); }) {}
  ~Queue() {
    {
      std::lock_guard<std::mutex> guard(mutex);
      stop = true;
    }
    changed.notify_all();
    thread.join();
  }

  void Run() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      changed.wait(lock, [this] { return stop || !pending.empty(); });
      if (pending.empty()) return;  // stopping, everything written
      DepthImages next = std::move(pending.front());
      lock.unlock();
      const Status written = error.ok() ? WriteImages(dir, next) : Status::Ok();
      lock.lock();
      pending.pop_front();
      if (!written.ok() && error.ok()) error = written;
      if (written.ok() && error.ok()) {
        stamps += StrFormat("%.9f %s\n", NsToSeconds(next.t_ns), next.index.c_str());
        ++written_count;
      }
      changed.notify_all();
    }
  }
  /// Waits until nothing is queued (lock held).
  void Drain(std::unique_lock<std::mutex>& lock) {
    changed.wait(lock, [this] { return pending.empty(); });
  }

  const std::string dir;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<DepthImages> pending;  // the front one is being written
  Status error = Status::Ok();      // the first failed write
  std::string stamps = "# t[s] index\n";
  int written_count = 0;
  bool stop = false;
  std::thread thread;  // last: starts once the members above exist
};

DepthFolderWriter::DepthFolderWriter(std::string dir)
    : dir_(std::move(dir)), queue_(std::make_unique<Queue>(dir_)) {}
DepthFolderWriter::DepthFolderWriter(DepthFolderWriter&&) noexcept = default;
DepthFolderWriter& DepthFolderWriter::operator=(DepthFolderWriter&&) noexcept = default;
DepthFolderWriter::~DepthFolderWriter() = default;

Expected<DepthFolderWriter> DepthFolderWriter::Create(const std::string& dir) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec) return IoError(dir + ": cannot remove the earlier maps (" + ec.message() + ")");
  fs::create_directories(dir, ec);
  if (ec) return IoError(dir + ": cannot create the folder (" + ec.message() + ")");
  return DepthFolderWriter(dir);
}

Expected<std::string> DepthFolderWriter::Add(TimeNs t_ns, const cv::Mat& disparity,
                                             const cv::Mat& picture) {
  if (disparity.type() != CV_16UC1)
    return InvalidArgument("DepthFolderWriter: the disparity image must be CV_16UC1");
  DepthImages images{t_ns, StrFormat("%06d", added_), disparity.clone(), picture.clone()};
  std::unique_lock<std::mutex> lock(queue_->mutex);
  queue_->changed.wait(lock, [this] { return queue_->pending.size() < kMaxQueued; });
  AAVIO_RETURN_IF_ERROR(queue_->error);
  queue_->pending.push_back(std::move(images));
  lock.unlock();
  queue_->changed.notify_all();
  ++added_;
  return StrFormat("%06d", added_ - 1);
}

Status DepthFolderWriter::Finish() {
  std::unique_lock<std::mutex> lock(queue_->mutex);
  queue_->Drain(lock);
  Status status = queue_->error;
  if (queue_->written_count == 0) {  // no map: no folder, rather than an index that lists nothing
    std::error_code ec;
    fs::remove_all(dir_, ec);
    return status;
  }
  const Status stamps = WriteTextFile((fs::path(dir_) / "timestamps.txt").string(), queue_->stamps);
  return status.ok() ? stamps : status;
}

int DepthFolderWriter::count() const {
  std::lock_guard<std::mutex> guard(queue_->mutex);
  return queue_->written_count;
}

}  // namespace aavio::io
