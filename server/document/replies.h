// What a document answers besides deltas (docs/PROTOCOL.md §5 and §8): the frame of a server message, and a
// Reject whose reason follows the failure's ErrorCode. The one mapping from a Status to a wire reason, used
// by hosts and connections alike.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::server {

// Builds the frame of a server message (length prefix + payload); null (and
// logged) when it cannot be encoded within `maxFrameBytes`.
std::shared_ptr<const std::string> frameOf(const wire::ServerMessage& message, uint32_t maxFrameBytes);

// The reason a Reject gives for a failure with `code`.
wire::RejectReason rejectReasonFor(ErrorCode code);
// An Ack of `clientSeq` for `documentId` (0: none); callers add a version or
// edit ids where the command has them.
wire::ServerMessage ackFor(uint64_t clientSeq, uint64_t documentId);
// A Reject for `clientSeq` with `reason` and the text that says why.
wire::ServerMessage rejectWith(uint64_t clientSeq, wire::RejectReason reason, const std::string& text);
// A Reject for a failed command, its reason chosen from the Status code.
wire::ServerMessage rejectFor(uint64_t clientSeq, const Status& status);
// The Reject of a document command that failed: undo and redo of an edit
// that cannot be undone or redone now give REJECT_REASON_INVALID_STATE; a
// batch's Reject names its refused command (`failedIndex`, from 1).
wire::ServerMessage rejectForCommand(uint64_t clientSeq, const wire::ClientMessage& command,
                                     uint32_t failedIndex, const Status& status);
// The frame of a reply to `clientSeq` built on a document's queue: `reply`
// framed, or a Reject saying why it cannot go -- its own failure, or
// `tooLarge` when it does not fit in `maxFrameBytes`.
std::shared_ptr<const std::string> replyOrReject(uint64_t clientSeq,
                                                 const Expected<wire::ServerMessage>& reply,
                                                 uint32_t maxFrameBytes, const std::string& tooLarge);
// A Reject with REJECT_REASON_LIMIT_EXCEEDED, framed: a request over a
// budget or cap (docs/PROTOCOL.md §9).
std::shared_ptr<const std::string> limitExceeded(uint64_t clientSeq, const std::string& message,
                                                 uint32_t maxFrameBytes);

}  // namespace tessera::server
