#pragma once
/// Status and Expected<T>: how aavio reports recoverable failures (bad input, missing files,
/// invalid configuration). The library never prints or exits; callers decide what to do.
/// Messages name the file, the field and the fix, e.g.
///   "calib/left.yaml: distortion_coefficients: declares 1x4 = 4 values but lists 5; set cols: 5".

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace aavio {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,     ///< a value is out of range or malformed (config, parameters)
  kNotFound,            ///< a file, key, topic or stream is missing
  kParseError,          ///< a file exists but its contents cannot be parsed
  kIoError,             ///< reading or writing failed at the OS level
  kFailedPrecondition,  ///< inputs are individually valid but inconsistent
  kOutOfRange,          ///< a query outside the available data (e.g. time outside a buffer)
  kUnimplemented,       ///< a feature that is not built yet
};

const char* StatusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return {}; }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

  /// Returns a copy whose message is prefixed with `context: ` (e.g. a file name or a section).
  Status WithContext(const std::string& context) const;

  /// "InvalidArgument: message", or "OK".
  std::string ToString() const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status InvalidArgument(std::string msg) {
  return {StatusCode::kInvalidArgument, std::move(msg)};
}
inline Status NotFound(std::string msg) {
  return {StatusCode::kNotFound, std::move(msg)};
}
inline Status ParseError(std::string msg) {
  return {StatusCode::kParseError, std::move(msg)};
}
inline Status IoError(std::string msg) {
  return {StatusCode::kIoError, std::move(msg)};
}
inline Status FailedPrecondition(std::string msg) {
  return {StatusCode::kFailedPrecondition, std::move(msg)};
}
inline Status OutOfRange(std::string msg) {
  return {StatusCode::kOutOfRange, std::move(msg)};
}
inline Status Unimplemented(std::string msg) {
  return {StatusCode::kUnimplemented, std::move(msg)};
}

/// A value or the Status explaining why there is none (std::expected is C++23).
template <typename T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : data_(std::move(value)) {}         // NOLINT: implicit by design
  Expected(Status status) : data_(std::move(status)) {}  // NOLINT: implicit by design

  bool ok() const { return std::holds_alternative<T>(data_); }
  explicit operator bool() const { return ok(); }

  const T& value() const& { return std::get<T>(data_); }
  T& value() & { return std::get<T>(data_); }
  T&& value() && { return std::get<T>(std::move(data_)); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  /// The error; Status::Ok() when a value is held.
  Status status() const { return ok() ? Status::Ok() : std::get<Status>(data_); }

 private:
  std::variant<T, Status> data_;
};

}  // namespace aavio

/// Returns from the enclosing function if `expr` (a Status) is not ok.
#define AAVIO_RETURN_IF_ERROR(expr)                \
  do {                                             \
    ::aavio::Status aavio_status_ = (expr);        \
    if (!aavio_status_.ok()) return aavio_status_; \
  } while (false)
