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

template <typename Io>
void RemoteSession::withSession(Io io) {
  bool open = false;
  {
    py::gil_scoped_release waiting;
    std::lock_guard<std::mutex> lock(mutex_);
    if (session_ != nullptr) {
      open = true;
      io(*session_);
    }
  }
  if (!open) throw Failure(invalidArgument("the session is closed"));
}

wire::ServerMessage RemoteSession::call(wire::ClientMessage message, std::optional<double> timeoutSeconds) {
  Expected<wire::ServerMessage> reply = ioError("no reply");
  const double timeout = timeoutSeconds.value_or(timeout_);
  withSession([&](client::Session& s) { reply = s.call(std::move(message), timeout); });
  return replyOf(std::move(reply));
}

void RemoteSession::send(wire::ClientMessage message) {
  Expected<uint64_t> sent = ioError("not sent");
  withSession([&](client::Session& s) { sent = s.send(std::move(message)); });
  check(sent.status());
}

std::optional<wire::ServerMessage> RemoteSession::receive(double timeoutSeconds) {
  Expected<wire::ServerMessage> next = ioError("nothing received");
  withSession([&](client::Session& s) {
    next = s.receive(timeoutSeconds);
    // Applied before another thread may read the next message, so that
    // the views see the messages in the order they came; the mutex is
    // always taken before the GIL, never the other way round.
    if (next.isOk()) {
      py::gil_scoped_acquire held;
      apply(*next);
    }
  });
  if (!next.isOk() && client::isReceiveTimeout(next.status())) return std::nullopt;
  check(next.status());
  if (next->has_error() && next->error().fatal())
    throw ServerFailure(next->error().code(), next->error().message(), true);
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
  {
    py::gil_scoped_release waiting;
    std::lock_guard<std::mutex> lock(mutex_);
    if (session_ != nullptr) session_->close();
    session_.reset();
  }
  closed_ = true;
  views_.clear();
}

}  // namespace tessera::python
