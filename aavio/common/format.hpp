#pragma once
/// printf-style formatting into a std::string, for messages (the compiler checks the format).

#include <cstdarg>
#include <cstdio>
#include <string>

namespace aavio {

__attribute__((format(printf, 1, 2))) inline std::string StrFormat(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  if (n < 0) return {};
  if (static_cast<std::size_t>(n) < sizeof(buffer))
    return std::string(buffer, static_cast<std::size_t>(n));
  std::string out(static_cast<std::size_t>(n), '\0');
  va_start(args, format);
  std::vsnprintf(out.data(), out.size() + 1, format, args);
  va_end(args);
  return out;
}

}  // namespace aavio
