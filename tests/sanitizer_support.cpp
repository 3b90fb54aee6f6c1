// Linked into the test programs of sanitizer builds (-DAAVIO_SANITIZE=ON) only.
//
// libblosc, which the HDF5 blosc plugin loads, allocates a small global context on first use and
// never frees it (3.4 kB once per process). HDF5 unloads the plugin before LeakSanitizer's check
// at exit, so the report has no module name to suppress it by. Keeping libblosc loaded makes its
// frames nameable, and the suppression below names exactly that library.
#include <dlfcn.h>

extern "C" const char* __lsan_default_suppressions() { return "leak:libblosc.so\n"; }

namespace {
[[maybe_unused]] void* const kKeepBloscLoaded = dlopen("libblosc.so.1", RTLD_NOW | RTLD_NODELETE);
}  // namespace
