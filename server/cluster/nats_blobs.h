// Blobs larger than one NATS message (a document's base, its snapshots) on
// a JetStream stream that keeps one message per subject: the chunks on
// <prefix>.0, <prefix>.1, ... and, written last, a manifest on <prefix>
// giving the size, the chunk count and a checksum. A reader that finds no
// manifest finds no blob, so a writer that dies half-way leaves nothing a
// reader would take for whole; the checksum refuses a blob whose chunks were
// overwritten by a later writer meanwhile.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/util/status.h"
#include "server/cluster/nats_link.h"

namespace tessera::cluster {

// At most; less when the NATS servers' max_payload is smaller (1 MiB by
// default), with room for headers.
inline constexpr size_t kBlobChunkBytes = 512 * 1024;

Status putBlob(NatsLink& link, const std::string& stream, const std::string& prefix, std::string_view bytes);
// kNotFound when there is no manifest; kParseError, naming `where`, when the
// chunks do not add up to what the manifest says.
Expected<std::string> getBlob(NatsLink& link, const std::string& stream, const std::string& prefix,
                              std::string_view where);

// The last message on `subject` (kNotFound when there is none), with its
// stream sequence.
struct LastMessage {
  std::string payload;
  uint64_t sequence = 0;
};
Expected<LastMessage> lastMessage(NatsLink& link, const std::string& stream, const std::string& subject);
// The first message on `subject` at or after stream sequence `from`
// (kNotFound when there is none), by a direct get: any replica answers, so
// it may lag the leader by the last few messages.
Expected<LastMessage> nextMessage(NatsLink& link, const std::string& stream, const std::string& subject,
                                  uint64_t from);
// nextMessage, asked again for up to about a second while it is kNotFound:
// the replica that answers may lag the leader (whose tail the caller read)
// by the last few messages. Still kNotFound after that.
Expected<LastMessage> nextMessageOnReplicas(NatsLink& link, const std::string& stream,
                                            const std::string& subject, uint64_t from);
// Removes every message on `subject` (a wildcard is allowed), one at a
// time by its stream sequence, as direct gets find them (a message a
// lagging replica has not seen yet may stay behind). Never a purge filtered
// by subject: nats-server before 2.9.17 replays such a purge as a purge of
// the whole stream when a clustered stream recovers after a restart
// (nats-io/nats-server issue 4196, fixed by its pull request 4197), and so
// every document's base and snapshots were lost after all NATS servers
// were killed at once (docs/CLUSTER.md "Fault-injection soak").
Status deleteMessagesOn(NatsLink& link, const std::string& stream, const std::string& subject);

}  // namespace tessera::cluster
