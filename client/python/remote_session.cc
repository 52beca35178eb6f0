#include "client/python/remote_session.h"

#include <pybind11/pybind11.h>

#include "client/python/errors.h"

namespace tessera::python {

namespace py = pybind11;

std::shared_ptr<RemoteSession> RemoteSession::connect(const client::SessionOptions& options) {
  wire::ErrorCode refusal = wire::ERROR_CODE_UNSPECIFIED;
  Expected<std::unique_ptr<client::Session>> session = ioError("not connected");
  {
    py::gil_scoped_release waiting;
    session = client::Session::connect(options, &refusal);
  }
  if (!session.isOk() && refusal != wire::ERROR_CODE_UNSPECIFIED) {
    // The handshake's Error is fatal: the server closes the connection.
    throw ServerFailure(refusal,
                        "tessera-server at " + options.host + ":" + std::to_string(options.port) + ": " +
                            session.status().message(),
                        true);
  }
  return std::shared_ptr<RemoteSession>(
      new RemoteSession(valueOf(std::move(session)), options.timeoutSeconds));
}

client::Session& RemoteSession::session() const {
  if (session_ == nullptr) throw Failure(invalidArgument("the session is closed"));
  return *session_;
}

wire::ServerMessage RemoteSession::call(wire::ClientMessage message, std::optional<double> timeoutSeconds) {
  client::Session& s = session();
  Expected<wire::ServerMessage> reply = ioError("no reply");
  {
    py::gil_scoped_release waiting;
    reply = s.call(std::move(message), timeoutSeconds.value_or(timeout_));
  }
  return replyOf(std::move(reply));
}

void RemoteSession::send(wire::ClientMessage message) {
  client::Session& s = session();
  Expected<uint64_t> sent = ioError("not sent");
  {
    py::gil_scoped_release waiting;
    sent = s.send(std::move(message));
  }
  check(sent.status());
}

std::optional<wire::ServerMessage> RemoteSession::receive(double timeoutSeconds) {
  client::Session& s = session();
  Expected<wire::ServerMessage> next = ioError("nothing received");
  {
    py::gil_scoped_release waiting;
    next = s.receive(timeoutSeconds);
  }
  if (!next.isOk() && client::isReceiveTimeout(next.status())) return std::nullopt;
  check(next.status());
  if (next->has_error() && next->error().fatal())
    throw ServerFailure(next->error().code(), next->error().message(), true);
  apply(*next);
  return std::move(next).value();
}

void RemoteSession::apply(const wire::ServerMessage& message) {
  roster_.apply(message);
  uint64_t document = 0;
  if (message.has_snapshot()) document = message.snapshot().document_id();
  if (message.has_delta()) document = message.delta().document_id();
  const auto held = views_.find(document);
  if (held == views_.end()) return;
  // A gap makes the view wait for a resync snapshot (DocumentView::
  // needsResync), which the caller sees there; anything else (a region
  // that does not decode) is an error of its own.
  Status applied = held->second->apply(message);
  if (!applied.isOk() && !held->second->needsResync()) throw Failure(applied);
}

std::shared_ptr<client::DocumentView> RemoteSession::watch(uint64_t document) {
  auto view = std::make_shared<client::DocumentView>(document);
  views_[document] = view;
  return view;
}

std::shared_ptr<client::DocumentView> RemoteSession::view(uint64_t document) const {
  const auto held = views_.find(document);
  return held == views_.end() ? nullptr : held->second;
}

void RemoteSession::close() {
  if (session_ == nullptr) return;
  session_->close();
  session_.reset();
  views_.clear();
}

}  // namespace tessera::python
