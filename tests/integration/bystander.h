// A bystander for abuse tests (abuse_test.cc): an editor and a viewer of a
// small document of their own, on another loopback address, measuring how
// long each edit takes to come back as a delta. An abuse test runs it
// before and during the abuse: every edit must still arrive, within a
// bound far above its normal latency (a stall of seconds fails, scheduling
// noise of a loaded 2-core machine does not).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera::testing {

class Bystander {
 public:
  struct Latencies {
    std::vector<double> ms;  // per edit, in order
    double median() const { return at(0.5); }
    double max() const { return ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end()); }
    double at(double q) const {
      if (ms.empty()) return 0;
      std::vector<double> s = ms;
      std::sort(s.begin(), s.end());
      return s[static_cast<size_t>(q * static_cast<double>(s.size() - 1))];
    }
  };

  // Creates its document through `admin` and connects from `address`.
  static Expected<std::unique_ptr<Bystander>> start(const ServerProcess& server, client::Session& admin,
                                                    const std::string& address = "127.0.0.9") {
    std::unique_ptr<Bystander> b(new Bystander);
    auto created =
        admin.call(createDocument("bystander", fileBytes(sourceTestDataPath("cube.obj")), "", 4), 30);
    if (!created.isOk()) return created.status();
    if (!created->has_ack()) return invalidArgument("bystander document refused: " + created->DebugString());
    b->doc_ = created->ack().document_id();
    auto options = server.session("bystander", server.adminToken());
    options.localAddress = address;
    TESSERA_ASSIGN_OR_RETURN(b->editor_, client::Session::connect(options));
    options.name = "bystander-viewer";
    TESSERA_ASSIGN_OR_RETURN(b->viewer_, client::Session::connect(options));
    b->view_ = std::make_unique<client::DocumentView>(b->doc_);
    for (client::Session* s : {b->editor_.get(), b->viewer_.get()}) {
      auto opened = s->call(openDocument(b->doc_), 20);
      if (!opened.isOk() || !opened->has_ack()) return ioError("bystander cannot open its document");
    }
    auto subscribed = b->viewer_->call(subscribe(b->doc_, 1, 3), 30);
    if (!subscribed.isOk() || !subscribed->has_ack()) return ioError("bystander cannot subscribe");
    TESSERA_RETURN_IF_ERROR(b->readUntil([&] { return b->view_->ready(); }, 30));
    return b;
  }

  uint64_t document() const { return doc_; }

  // `edits` small moves sent every `interval` whatever happens meanwhile
  // (an open loop: a stalled server shows as latency of every edit sent
  // during the stall, not as fewer samples), each timed from its send until
  // the viewer has applied a delta reaching its version (deltas leave when
  // encoded; acks wait for the journal and are read without waiting, then
  // checked by awaitAcks). Only this editor edits the document, so the k-th
  // edit's version is the view's version before the run plus k.
  Expected<Latencies> run(int edits, std::chrono::milliseconds interval = std::chrono::milliseconds(20)) {
    int sentSoFar = 0;
    return runUntil([&] { return ++sentSoFar > edits; }, interval);
  }

  // The same, sending until `stop()` (asked before each edit) says so.
  template <typename Stop>
  Expected<Latencies> runUntil(Stop stop,
                               std::chrono::milliseconds interval = std::chrono::milliseconds(20)) {
    using Clock = std::chrono::steady_clock;
    const uint64_t first = view_->version() + 1;
    std::vector<Clock::time_point> sent;  // guarded by mutex
    std::mutex mutex;
    std::atomic<bool> senderDone{false};
    Status sending = Status::ok();
    std::thread sender([&] {
      auto next = Clock::now();
      while (sending.isOk() && !stop()) {
        std::this_thread::sleep_until(next);
        next += interval;
        const double dz = (step_++ % 2 == 0) ? 0.01 : -0.01;
        {
          std::lock_guard lock(mutex);
          sent.push_back(Clock::now());
        }
        auto seq = editor_->send(moveVertex(doc_, VertexId(1, 2).packed(), 0, 0, dz, wire::MOVE_MODE_OFFSET));
        if (!seq.isOk()) sending = seq.status();
        if (seq.isOk()) ++unacked_;
        // Acks that have come, without waiting: the loop stays open.
        while (sending.isOk() && unacked_ > 0) {
          auto m = editor_->receive(0.0);
          if (!m.isOk()) {
            if (!client::isReceiveTimeout(m.status())) sending = m.status();
            break;
          }
          if (client::replyTo(*m) == 0) continue;
          if (!m->has_ack()) sending = invalidArgument("bystander edit refused: " + m->DebugString());
          --unacked_;
        }
      }
      senderDone = true;
    });
    // Applied-at times per version, read on this thread.
    std::vector<Clock::time_point> arrived;
    Status reading = readUntil(
        [&] {
          const bool last = senderDone.load();
          std::lock_guard lock(mutex);
          while (arrived.size() < static_cast<size_t>(view_->version() + 1 - first) &&
                 arrived.size() < sent.size()) {
            arrived.push_back(Clock::now());
          }
          return last && arrived.size() == sent.size();
        },
        600);
    sender.join();
    TESSERA_RETURN_IF_ERROR(sending);
    TESSERA_RETURN_IF_ERROR(reading);
    Latencies out;
    for (size_t i = 0; i < arrived.size(); ++i) {
      out.ms.push_back(std::chrono::duration<double, std::milli>(arrived[i] - sent[i]).count());
    }
    return out;
  }

  // Waits for the acks of every edit sent so far: each acknowledged, none
  // refused.
  Status awaitAcks(double seconds = 60) {
    while (unacked_ > 0) {
      auto m = editor_->receive(seconds);
      if (!m.isOk()) return m.status();
      if (client::replyTo(*m) == 0) continue;
      if (!m->has_ack()) return invalidArgument("bystander edit refused: " + m->DebugString());
      --unacked_;
    }
    return Status::ok();
  }

 private:
  Bystander() = default;
  // Applies the viewer's messages until `done()`, polling so that `done`
  // is asked at least every 50 ms even when nothing arrives.
  template <typename Done>
  Status readUntil(Done done, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline)
        return ioError("bystander: not done within " + std::to_string(seconds) + " s");
      auto m = viewer_->receive(0.05);
      if (!m.isOk()) {
        if (client::isReceiveTimeout(m.status())) continue;
        return m.status();
      }
      TESSERA_RETURN_IF_ERROR(view_->apply(*m));
    }
    return Status::ok();
  }

  uint64_t doc_ = 0;
  int step_ = 0;
  int64_t unacked_ = 0;  // edits sent whose ack has not been read
  std::unique_ptr<client::Session> editor_, viewer_;
  std::unique_ptr<client::DocumentView> view_;
};

}  // namespace tessera::testing
