#include "aavio/io/formats/dsec_h5/hdf5_util.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
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

Status SurvivesInChild(const std::string& path, const std::function<void()>& attempt,
                       double timeout_s) {
#if defined(__unix__)
  const pid_t child = fork();
  if (child < 0) return Status::Ok();  // no probe, as where fork does not exist
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
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (auto wait = std::chrono::microseconds(200);;
       wait = std::min(2 * wait, std::chrono::microseconds(20'000))) {
    int status = 0;
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) {
      if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return Status::Ok();
      // Killed by a signal, or ended otherwise (a sanitizer's report, an abort handler).
      const std::string how =
          WIFSIGNALED(status)
              ? "signal " + std::to_string(WTERMSIG(status)) + ", " + strsignal(WTERMSIG(status))
              : "exit status " + std::to_string(WEXITSTATUS(status));
      return ParseError(path + ": the HDF5 library crashed (" + how +
                        ") reading the file's structure: the file is corrupt. `h5dump -H " + path +
                        "` shows where; export or download it again");
    }
    if (done < 0) return Status::Ok();  // the child was reaped elsewhere
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return ParseError(path +
                        ": the HDF5 library did not finish reading the file's structure in " +
                        std::to_string(static_cast<int>(timeout_s)) +
                        " s: the file is corrupt (or its file system hangs)");
    }
    std::this_thread::sleep_for(wait);
  }
#else
  (void)path;
  (void)attempt;
  (void)timeout_s;
  return Status::Ok();
#endif
}

}  // namespace aavio::io::h5
