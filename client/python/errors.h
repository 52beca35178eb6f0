// How failures reach Python (docs/PYTHON.md "Errors"): C++ exceptions
// thrown by the bindings, translated into the tessera exception classes.
// They carry no Python objects, so they may be thrown while the GIL is
// released (a blocking call) and translated once it is held again.
//
//   tessera.Error                 a tessera::Status that is not ok
//     tessera.Timeout             nothing arrived in time (ErrorCode::kTimeout)
//     tessera.Rejected            a command's Reject (docs/PROTOCOL.md §8.1)
//     tessera.ServerError         the server's Error message (§8.2)
//       tessera.AuthenticationFailed   ERROR_CODE_AUTH_FAILED at the handshake
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::python {

struct Failure : std::runtime_error {
  explicit Failure(const Status& status);
  std::string code;  // errorCodeName(): "not found", "parse error", ...
  bool timedOut;     // ErrorCode::kTimeout: tessera.Timeout
};

struct Rejection : std::runtime_error {
  explicit Rejection(const wire::Reject& reject);
  int reasonCode;
  std::string reason;  // RejectReason_Name: "REJECT_REASON_NOT_FOUND"
  std::string message;
  uint32_t batchIndex;
};

struct ServerFailure : std::runtime_error {
  ServerFailure(wire::ErrorCode code, const std::string& text, bool fatal);
  int errorCode;
  std::string code;  // ErrorCode_Name: "ERROR_CODE_AUTH_FAILED"
  bool fatal;
};

// Throws the Failure for a status that is not ok.
void check(const Status& status);
template <typename T>
T valueOf(Expected<T> result) {
  check(result.status());
  return std::move(result).value();
}

// A command's reply: returned when it is one, thrown (Rejection,
// ServerFailure, Failure) when it is a Reject, an Error or a failed call.
wire::ServerMessage replyOf(Expected<wire::ServerMessage> reply);

}  // namespace tessera::python
