// Linked into the fuzz targets of sanitizer builds. As tests/sanitizer_support.cpp (libblosc's
// context, allocated once and never freed), and: HDF5 1.10 itself leaks a few hundred bytes on
// some corrupt files (H5Fopen then H5Fclose, in a program of those two calls alone, leaks). That
// is the library's, not aavio's (every HDF5 id aavio opens is closed by h5::Handle), so leaks
// allocated inside libhdf5 are not reported here; the unit tests still report them.
#include <dlfcn.h>

extern "C" const char* __lsan_default_suppressions() {
  return "leak:libblosc.so\nleak:libhdf5_serial.so\n";
}

namespace {
[[maybe_unused]] void* const kKeepBloscLoaded = dlopen("libblosc.so.1", RTLD_NOW | RTLD_NODELETE);
}  // namespace
