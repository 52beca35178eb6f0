// What a tessera.Session holds (docs/PYTHON.md "Sessions"): one
// client::Session, the views of the documents it subscribed to and their
// presence, kept current from every message it reads. Each blocking call
// releases the GIL while it waits, and holds a mutex instead: calls from
// several Python threads take turns on the one connection, as
// client::Session requires.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "client/python/presence_roster.h"

namespace tessera::python {

class RemoteSession {
 public:
  // Connects and says hello; throws Failure, or ServerFailure when the
  // server refuses the handshake (an unknown token: ERROR_CODE_AUTH_FAILED).
  static std::shared_ptr<RemoteSession> connect(const client::SessionOptions& options);

  // The connection's timeout (SessionOptions::timeoutSeconds): the wait
  // for any reply when a call gives none.
  double timeout() const { return timeout_; }
  uint64_t sessionId() const { return sessionId_; }
  wire::Role role() const { return role_; }

  // Sends a command and returns its reply (Ack, DocumentList, ...); throws
  // Rejection, ServerFailure or Failure (replyOf). Messages that arrive
  // meanwhile are applied in order, as receive() would.
  wire::ServerMessage call(wire::ClientMessage message, std::optional<double> timeoutSeconds);
  // Sends a command that gets no reply when valid (select, set_view).
  void send(wire::ClientMessage message);
  // The next message, applied to the views and the presence it concerns;
  // nothing when none arrives within the timeout. A fatal Error throws.
  std::optional<wire::ServerMessage> receive(double timeoutSeconds);

  // The view a subscribe starts (replacing one held) and the one held.
  std::shared_ptr<client::DocumentView> watch(uint64_t document);
  std::shared_ptr<client::DocumentView> view(uint64_t document) const;
  void stopWatching(uint64_t document) { views_.erase(document); }
  // Puts back a view watch() replaced (a refused subscribe); null: none.
  void restoreView(uint64_t document, std::shared_ptr<client::DocumentView> view) {
    if (view)
      views_[document] = std::move(view);
    else
      views_.erase(document);
  }
  const PresenceRoster& presence() const { return roster_; }

  void close();
  bool closed() const { return closed_; }

 private:
  RemoteSession(std::unique_ptr<client::Session> session, double timeoutSeconds)
      : session_(std::move(session)),
        timeout_(timeoutSeconds),
        sessionId_(session_->sessionId()),
        role_(session_->role()) {}
  // Runs `io` on the session with the GIL released and the mutex held;
  // throws Failure when the session is closed.
  template <typename Io>
  void withSession(Io io);
  void apply(const wire::ServerMessage& message);

  std::mutex mutex_;  // guards session_
  std::unique_ptr<client::Session> session_;
  std::atomic<bool> closed_ = false;
  double timeout_;
  uint64_t sessionId_;
  wire::Role role_;
  std::map<uint64_t, std::shared_ptr<client::DocumentView>> views_;
  PresenceRoster roster_;
};

}  // namespace tessera::python
