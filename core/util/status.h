// Status and Expected<T>: the one error convention inside Tessera.
//
// Every fallible function returns a Status (no value) or an Expected<T>
// (a value or a Status). Messages name the file, the element and the reason,
// so that the edges (CLI, server) can print them unchanged.
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace tessera {

enum class ErrorCode {
  kOk = 0,
  kInvalidArgument,  // a caller passed something malformed (bad option, NaN, ...)
  kParseError,       // a file or text could not be parsed
  kInvalidMesh,      // the mesh parsed but violates a topological/geometric rule
  kNotFound,         // an id, file or element does not exist
  kUnsupported,      // a format or feature Tessera does not handle
  kIoError,          // the operating system refused a read or write
  kTimeout,          // no answer in time: what was asked may or may not have happened
  kUnavailable,      // a service needed is not reachable now (no quorum, no responders)
  kInternal,         // a broken invariant: a bug in Tessera
};

const char* errorCodeName(ErrorCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(ErrorCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status ok() { return Status(); }

  bool isOk() const { return code_ == ErrorCode::kOk; }
  ErrorCode code() const { return code_; }
  const std::string& message() const { return message_; }

  // "invalid mesh: cube.obj: face 3: ..." -- the form printed at the edges.
  std::string toString() const;

  // Prefixes context, e.g. the file name, keeping the code.
  Status withContext(const std::string& context) const;

 private:
  ErrorCode code_ = ErrorCode::kOk;
  std::string message_;
};

inline Status invalidArgument(std::string m) {
  return {ErrorCode::kInvalidArgument, std::move(m)};
}
inline Status parseError(std::string m) {
  return {ErrorCode::kParseError, std::move(m)};
}
inline Status invalidMesh(std::string m) {
  return {ErrorCode::kInvalidMesh, std::move(m)};
}
inline Status notFound(std::string m) {
  return {ErrorCode::kNotFound, std::move(m)};
}
inline Status unsupported(std::string m) {
  return {ErrorCode::kUnsupported, std::move(m)};
}
inline Status ioError(std::string m) {
  return {ErrorCode::kIoError, std::move(m)};
}
inline Status internalError(std::string m) {
  return {ErrorCode::kInternal, std::move(m)};
}
inline Status timeoutError(std::string m) {
  return {ErrorCode::kTimeout, std::move(m)};
}
inline Status unavailableError(std::string m) {
  return {ErrorCode::kUnavailable, std::move(m)};
}

// A failure that may pass if tried again later: the operating system's,
// a timeout, or a service not reachable now.
inline bool isTransient(const Status& status) {
  return status.code() == ErrorCode::kIoError || status.code() == ErrorCode::kTimeout ||
         status.code() == ErrorCode::kUnavailable;
}

template <typename T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : data_(std::move(value)) {}        // NOLINT: implicit by design
  Expected(Status status) : data_(std::move(status)) {  // NOLINT: implicit by design
    assert(!std::get<Status>(data_).isOk() && "Expected built from an ok Status");
  }

  bool isOk() const { return std::holds_alternative<T>(data_); }
  explicit operator bool() const { return isOk(); }

  const Status& status() const {
    static const Status kOk;
    return isOk() ? kOk : std::get<Status>(data_);
  }

  T& value() & { return std::get<T>(data_); }
  const T& value() const& { return std::get<T>(data_); }
  T&& value() && { return std::get<T>(std::move(data_)); }

  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Status> data_;
};

}  // namespace tessera

#define TESSERA_CONCAT_INNER(a, b) a##b
#define TESSERA_CONCAT(a, b) TESSERA_CONCAT_INNER(a, b)

#define TESSERA_RETURN_IF_ERROR(expr)                    \
  do {                                                   \
    ::tessera::Status tessera_status_ = (expr);          \
    if (!tessera_status_.isOk()) return tessera_status_; \
  } while (0)

#define TESSERA_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                  \
  if (!tmp.isOk()) return tmp.status();               \
  lhs = std::move(tmp).value()

#define TESSERA_ASSIGN_OR_RETURN(lhs, expr) \
  TESSERA_ASSIGN_OR_RETURN_IMPL(TESSERA_CONCAT(tessera_expected_, __LINE__), lhs, expr)
