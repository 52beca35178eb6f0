#include "client/python/errors.h"

#include "client/python/bindings.h"

namespace tessera::python {

Failure::Failure(const Status& status)
    : std::runtime_error(status.message()),
      code(errorCodeName(status.code())),
      timedOut(status.code() == ErrorCode::kTimeout) {}

Rejection::Rejection(const wire::Reject& reject)
    : std::runtime_error(wire::RejectReason_Name(reject.reason()) + ": " + reject.message()),
      reasonCode(reject.reason()),
      reason(wire::RejectReason_Name(reject.reason())),
      message(reject.message()),
      batchIndex(reject.batch_index()) {
  // A newer server may send a reason this client does not know by name.
  if (reason.empty()) reason = "reject reason " + std::to_string(reasonCode);
}

ServerFailure::ServerFailure(wire::ErrorCode code, const std::string& text, bool fatal)
    : std::runtime_error(text), errorCode(code), code(wire::ErrorCode_Name(code)), fatal(fatal) {
  if (this->code.empty()) this->code = "error code " + std::to_string(errorCode);
}

void check(const Status& status) {
  if (!status.isOk()) throw Failure(status);
}

wire::ServerMessage replyOf(Expected<wire::ServerMessage> reply) {
  check(reply.status());
  if (reply->has_reject()) throw Rejection(reply->reject());
  if (reply->has_error()) {
    const wire::Error& e = reply->error();
    throw ServerFailure(e.code(), wire::ErrorCode_Name(e.code()) + ": " + e.message(), e.fatal());
  }
  return std::move(reply).value();
}

namespace {

// The exception classes, created once by bindErrors and kept for the
// module's lifetime (a module is never unloaded).
PyObject* errorType = nullptr;
PyObject* timeoutType = nullptr;
PyObject* rejectedType = nullptr;
PyObject* serverErrorType = nullptr;
PyObject* authenticationFailedType = nullptr;

PyObject* newType(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string("tessera.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

// Raises an instance of `type` with `text` as its message and the given
// attributes, so that `except tessera.Rejected as e: e.reason` works.
void raise(PyObject* type, const std::string& text, const py::dict& attributes) {
  py::object exception = py::reinterpret_borrow<py::object>(type)(text);
  for (auto [key, value] : attributes) exception.attr(key) = value;
  PyErr_SetObject(type, exception.ptr());
}

}  // namespace

void bindErrors(py::module_& m) {
  errorType = newType(m, "Error", PyExc_RuntimeError,
                      "A failure of the tessera client or core.\n\n"
                      "Attributes:\n"
                      "    code (str): what kind of failure, as core names it: 'not found',\n"
                      "        'parse error', 'invalid mesh', 'i/o error', 'timed out', ...");
  timeoutType = newType(m, "Timeout", errorType,
                        "Nothing arrived from the server in time; the connection is still usable.");
  rejectedType = newType(m, "Rejected", errorType,
                         "The server refused a command; the command had no effect and the\n"
                         "connection stays open (docs/PROTOCOL.md section 8.1).\n\n"
                         "Attributes:\n"
                         "    reason (str): the reject reason's name, e.g. 'REJECT_REASON_NOT_FOUND'.\n"
                         "    reason_code (int): its number in tessera.proto.\n"
                         "    message (str): the server's explanation, naming the element.\n"
                         "    batch_index (int): for an edit batch, the refused command from 1; else 0.");
  serverErrorType = newType(m, "ServerError", errorType,
                            "The server sent an Error: a problem with the connection rather than\n"
                            "with one command (docs/PROTOCOL.md section 8.2).\n\n"
                            "Attributes:\n"
                            "    code (str): the error code's name, e.g. 'ERROR_CODE_AUTH_FAILED'.\n"
                            "    error_code (int): its number in tessera.proto.\n"
                            "    fatal (bool): the server closes the connection after it.");
  authenticationFailedType = newType(m, "AuthenticationFailed", serverErrorType,
                                     "The server does not know the token given to Session.connect.");

  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Rejection& e) {
      raise(rejectedType, e.what(),
            py::dict(py::arg("reason") = e.reason, py::arg("reason_code") = e.reasonCode,
                     py::arg("message") = e.message, py::arg("batch_index") = e.batchIndex));
    } catch (const ServerFailure& e) {
      PyObject* type =
          e.errorCode == wire::ERROR_CODE_AUTH_FAILED ? authenticationFailedType : serverErrorType;
      raise(type, e.what(),
            py::dict(py::arg("code") = e.code, py::arg("error_code") = e.errorCode,
                     py::arg("fatal") = e.fatal));
    } catch (const Failure& e) {
      raise(e.timedOut ? timeoutType : errorType, e.what(), py::dict(py::arg("code") = e.code));
    }
  });
}

}  // namespace tessera::python
