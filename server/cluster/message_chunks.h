// Node-to-node messages of any size over NATS, whose servers refuse a
// message above their max_payload (1 MiB by default): a message that does
// not fit goes as consecutive chunks on the same subject, and the receiver
// puts them back together. Chunks of one message come from one publisher on
// one subject, so NATS keeps them in order and in order with that
// publisher's other messages: a large snapshot and the delta after it reach
// the receiving node in that order.
//
//   whole:  0x00 | the message
//   chunk:  0x01 | sender length (u8) | sender | message id (u64 LE)
//                | part (u32 LE) | parts (u32 LE) | data
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "core/util/status.h"
#include "server/cluster/nats_link.h"

namespace tessera::cluster {

// Publishes `message` on `subject`, in chunks when it does not fit the
// connection's max_payload. `sender` names this node (chunks are keyed by it).
Status publishMessage(NatsLink& link, const std::string& subject, const std::string& sender,
                      std::string_view message);

// Puts chunked messages back together, per sender. Bounded: at most
// `maxPartialBytes` held in unfinished messages (the oldest go first).
class ChunkAssembler {
 public:
  explicit ChunkAssembler(size_t maxPartialBytes = size_t{256} << 20) : maxPartialBytes_(maxPartialBytes) {}
  // The message `payload` completes, if any; an error names what is wrong
  // with a payload that is not a cluster message or a chunk out of order.
  Expected<std::optional<std::string>> add(std::string_view payload);

 private:
  struct Partial {
    uint64_t id = 0;
    uint32_t next = 0, parts = 0;
    std::string bytes;
    uint64_t age = 0;
  };
  std::mutex mutex_;
  std::map<std::string, Partial> partial_;  // by sender: one message at a time per sender and subject
  size_t held_ = 0;
  const size_t maxPartialBytes_;
  uint64_t clock_ = 0;
};

}  // namespace tessera::cluster
