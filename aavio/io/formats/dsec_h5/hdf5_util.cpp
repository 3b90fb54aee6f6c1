#include "aavio/io/formats/dsec_h5/hdf5_util.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#if defined(__unix__)
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

// Provided by a sanitizer runtime when one is linked in (a fuzzing or sanitizer build); null
// otherwise.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));
#endif

namespace aavio::io::h5 {

void SilenceErrorPrinting() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

namespace {

herr_t CollectMessage(unsigned /*n*/, const H5E_error2_t* error, void* data) {
  auto* messages = static_cast<std::string*>(data);
  if (error && error->desc && *error->desc) {
    if (!messages->empty()) *messages += "; ";
    *messages += error->desc;
  }
  return 0;
}

}  // namespace

std::string TakeErrorMessage() {
  std::string messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, CollectMessage, &messages);
  H5Eclear2(H5E_DEFAULT);
  return messages;
}

Status CheckReadable(hid_t dataset, const std::string& file, const std::string& name) {
  Handle plist(H5Dget_create_plist(dataset), H5Pclose);
  if (!plist.valid()) return IoError(file + ": " + name + ": cannot read its storage properties");
  const int count = H5Pget_nfilters(plist.get());
  for (int i = 0; i < count; ++i) {
    unsigned flags = 0;
    size_t n_values = 0;
    unsigned config = 0;
    char filter_name[128] = {0};
    const H5Z_filter_t id = H5Pget_filter2(plist.get(), static_cast<unsigned>(i), &flags, &n_values,
                                           nullptr, sizeof(filter_name), filter_name, &config);
    if (id < 0) continue;
    if (H5Zfilter_avail(id) > 0) continue;
    H5Eclear2(H5E_DEFAULT);
    if (id == 32001) {
      return FailedPrecondition(
          file + ": " + name +
          " is compressed with the blosc filter (HDF5 filter 32001), which is not installed; "
          "install the Debian package hdf5-filter-plugin-blosc-serial (scripts/setup.sh does) and "
          "leave HDF5_PLUGIN_PATH unset so HDF5 finds it");
    }
    std::string hint;
    if (id == 32015)
      hint = " (zstd; no Debian package provides it: recompress the file with blosc)";
    if (id == 32000) hint = " (lzf: install hdf5-plugin-lzf)";
    if (id == 32004 || id == 307) hint = " (install hdf5-filter-plugin)";
    return FailedPrecondition(file + ": " + name + " needs HDF5 filter " + std::to_string(id) +
                              " '" + filter_name + "', which is not available" + hint);
  }
  // Numbers of 1 to 8 bytes: HDF5 1.10 converts a corrupt file's absurd element type (a 33 MB
  // "integer") by reading past its own buffers (found by fuzzing).
  Handle type(H5Dget_type(dataset), H5Tclose);
  const std::size_t type_size = type.valid() ? H5Tget_size(type.get()) : 0;
  const H5T_class_t type_class = type.valid() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  if ((type_class != H5T_INTEGER && type_class != H5T_FLOAT) || type_size < 1 || type_size > 8) {
    H5Eclear2(H5E_DEFAULT);
    return ParseError(file + ": " + name + " holds elements of " + std::to_string(type_size) +
                      " bytes, not numbers of 1 to 8 bytes: a corrupt file?");
  }
  // A compact dataset keeps its bytes in its header; HDF5 1.10 trusts the shape over the bytes
  // stored, so a corrupt file that declares more would be read past them.
  if (H5Pget_layout(plist.get()) == H5D_COMPACT) {
    Handle space(H5Dget_space(dataset), H5Sclose);
    const hssize_t points = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
    const hsize_t stored = H5Dget_storage_size(dataset);
    if (points < 0 || stored < static_cast<hsize_t>(points) * static_cast<hsize_t>(type_size)) {
      H5Eclear2(H5E_DEFAULT);
      return ParseError(file + ": " + name + " stores " + std::to_string(stored) +
                        " bytes, fewer than its shape needs: a corrupt file");
    }
  }
  return Status::Ok();
}

bool LinkExists(hid_t file, const char* path) {
  // Check each component: H5Lexists fails on a path whose parent group is missing.
  std::string partial;
  std::string rest = path;
  while (!rest.empty()) {
    const std::size_t slash = rest.find('/', 1);
    partial += rest.substr(0, slash);
    rest = slash == std::string::npos ? "" : rest.substr(slash);
    if (H5Lexists(file, partial.c_str(), H5P_DEFAULT) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
  }
  return true;
}

#if defined(__unix__)
namespace {

/// The number of threads of this process (1 where /proc is not mounted: then fork is assumed
/// safe, as it always was).
int ThreadCount() {
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status) return 1;
  char line[256];
  int threads = 1;
  while (std::fgets(line, sizeof(line), status)) {
    if (std::sscanf(line, "Threads: %d", &threads) == 1) break;
  }
  std::fclose(status);
  return threads;
}

/// A child's scheduling state and CPU time (clock ticks) from /proc; false when unreadable.
bool ReadChildState(pid_t child, char* state, long long* cpu_ticks) {
  const std::string file = "/proc/" + std::to_string(child) + "/stat";
  std::FILE* stat = std::fopen(file.c_str(), "r");
  if (!stat) return false;
  char text[1024] = {0};
  const std::size_t n = std::fread(text, 1, sizeof(text) - 1, stat);
  std::fclose(stat);
  // "pid (comm) state ppid ..."; comm may hold spaces and parentheses: parse after the last ')'.
  const char* close = std::strrchr(text, ')');
  if (n == 0 || !close) return false;
  long long utime = 0, stime = 0;
  // state ppid pgrp session tty_nr tpgid flags minflt cminflt majflt cmajflt utime stime
  if (std::sscanf(close + 1, " %c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lld %lld", state, &utime,
                  &stime) != 3)
    return false;
  *cpu_ticks = utime + stime;
  return true;
}

enum class ProbeEnd { kSurvived, kCrashed, kTimedOut, kStalled };

struct Probe {
  ProbeEnd end = ProbeEnd::kSurvived;
  std::string how;  // kCrashed: the signal or exit status
};

/// One child: how it ended. With `stall_s` > 0, a child asleep without using any CPU for that
/// long is stopped as stalled.
Probe ProbeInChild(const std::function<void()>& attempt, double timeout_s, double stall_s) {
  const pid_t child = fork();
  if (child < 0) return {};  // no probe, as where fork does not exist
  if (child == 0) {
    // A crash here is the parent's finding, not the child's: drop handlers inherited from a
    // harness (a fuzzer writing a crash report, a sanitizer's death callback) so that the child
    // just dies of the signal.
    for (const int signal : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL})
      std::signal(signal, SIG_DFL);
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    attempt();
    _exit(0);  // the child only: no atexit handlers, no flush of the caller's buffers
  }
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  auto progress_at = Clock::now();
  long long last_ticks = -1;
  for (auto wait = std::chrono::microseconds(200);;
       wait = std::min(2 * wait, std::chrono::microseconds(20'000))) {
    int status = 0;
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) {
      if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
      // Killed by a signal, or ended otherwise (a sanitizer's report, an abort handler).
      return {ProbeEnd::kCrashed, WIFSIGNALED(status)
                                      ? "signal " + std::to_string(WTERMSIG(status)) + ", " +
                                            strsignal(WTERMSIG(status))
                                      : "exit status " + std::to_string(WEXITSTATUS(status))};
    }
    if (done < 0) return {};  // the child was reaped elsewhere
    const auto now = Clock::now();
    ProbeEnd stop = ProbeEnd::kSurvived;
    if (now > deadline) stop = ProbeEnd::kTimedOut;
    char state = 0;
    long long ticks = 0;
    if (stall_s > 0 && ReadChildState(child, &state, &ticks)) {
      if (state != 'S' || ticks != last_ticks) progress_at = now;
      last_ticks = ticks;
      if (std::chrono::duration<double>(now - progress_at).count() > stall_s)
        stop = ProbeEnd::kStalled;
    }
    if (stop != ProbeEnd::kSurvived) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return {stop, ""};
    }
    std::this_thread::sleep_for(wait);
  }
}

}  // namespace
#endif

Status SurvivesInChild(const std::string& path, const std::function<void()>& attempt,
                       double timeout_s) {
#if defined(__unix__)
  // fork copies only the calling thread. In a process of one thread the child starts with every
  // lock free; with other threads running, one of them may hold a lock at that instant (HDF5's
  // own, or the allocator's in a sanitizer build) that the child then waits for forever. Such a
  // child sleeps without using CPU: it is stopped and the probe forked again, the lock most
  // likely free by then; a child that stalls every time is an error that says so. HDF5 stuck on
  // a corrupt file spins or reads instead, and is stopped at the deadline.
  constexpr int kForks = 5;
  constexpr double kStallS = 1.0;
  const bool alone = ThreadCount() <= 1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (int fork_count = 1;; ++fork_count) {
    const double left_s =
        std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    const Probe probe = ProbeInChild(attempt, std::max(left_s, 0.0), alone ? 0.0 : kStallS);
    switch (probe.end) {
      case ProbeEnd::kSurvived:
        return Status::Ok();
      case ProbeEnd::kCrashed:
        return ParseError(path + ": the HDF5 library crashed (" + probe.how +
                          ") reading the file's structure: the file is corrupt. `h5dump -H " +
                          path + "` shows where; export or download it again");
      case ProbeEnd::kTimedOut:
        return ParseError(path +
                          ": the HDF5 library did not finish reading the file's structure in " +
                          std::to_string(static_cast<int>(timeout_s)) +
                          " s: the file is corrupt (or its file system hangs)");
      case ProbeEnd::kStalled:
        if (fork_count < kForks && left_s > 0) {
          std::this_thread::sleep_for(std::chrono::milliseconds(50 * fork_count));
          continue;
        }
        return ParseError(path + ": reading the file's structure in a child process stalled " +
                          std::to_string(fork_count) +
                          " times (another thread of this process holds a lock it needs, or "
                          "HDF5 deadlocks on a corrupt file): open the file before starting "
                          "other threads, or check it with `h5dump -H " +
                          path + "`");
    }
  }
#else
  (void)path;
  (void)attempt;
  (void)timeout_s;
  return Status::Ok();
#endif
}

}  // namespace aavio::io::h5
