// The owner's side of fan-out across nodes (docs/CLUSTER.md, "Any node serves any client"): a session of
// another node joins the owner's document host as a RemoteSubscriber, and
// what the host sends it goes to that node through the FrameRelay.
//
// The host sends a delta to its subscribers one after another in one task,
// the same frame (encoded once) to each. The relay merges consecutive sends
// of one frame to one node into one Frames message listing the sessions, so
// a node receives each delta once however many of its sessions watch, and
// then fans it out to their bounded queues (framesToOutgoing).
#pragma once

#include <nats/nats.h>

#include <boost/asio/any_io_executor.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "protocol/cluster.pb.h"
#include "server/cluster/nats_link.h"
#include "server/document/subscriber.h"

namespace tessera::cluster {

class FrameRelay {
 public:
  // Publishes on `link` as node `sender` (in chunks when a frame is larger
  // than NATS takes in one message) from tasks posted to `executor`.
  FrameRelay(NatsLink& link, std::string sender, boost::asio::any_io_executor executor)
      : link_(link), sender_(std::move(sender)), executor_(executor) {}

  // Queues `message` for `session` of `node`; a publish follows soon.
  void send(const std::string& node, uint64_t session, const server::Outgoing& message);
  // Sends `message` (a NotOwner) to `node` at once.
  void publish(const std::string& node, const NodeMessage& message);

  uint64_t framesPublished() const;

 private:
  struct Pending {
    std::shared_ptr<const std::string> frame;
    Frames message;  // without its frame bytes until published
  };
  void flush();

  NatsLink& link_;
  const std::string sender_;
  boost::asio::any_io_executor executor_;
  mutable std::mutex mutex_;
  std::map<std::string, std::vector<Pending>> pending_;  // by node, in send order
  bool flushPosted_ = false;
  uint64_t published_ = 0;
};

// A session of another node, as the owner's host sees it.
class RemoteSubscriber : public server::Subscriber {
 public:
  RemoteSubscriber(FrameRelay& relay, std::string node, uint64_t session)
      : relay_(relay), node_(std::move(node)), session_(session) {}
  uint64_t sessionId() const override { return session_; }
  void send(server::Outgoing message) override { relay_.send(node_, session_, message); }
  const std::string& node() const { return node_; }

 private:
  FrameRelay& relay_;
  const std::string node_;
  const uint64_t session_;
};

// What a node's outboxes get from a Frames message: its frame, with the
// delta's regions rebuilt from the frame so that queued deltas still merge.
// A frame that does not decode is refused by name.
Expected<server::Outgoing> framesToOutgoing(const Frames& frames, uint32_t maxFrameBytes);

// The subject a node reads `kind` messages on: tessera.node.<node>.<kind>.
std::string nodeSubject(const std::string& node, const char* kind);

}  // namespace tessera::cluster
