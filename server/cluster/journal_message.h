// The payload of one journal message on a document's JetStream subject
// (tessera.journal.<id>): the entry's version, its author and the opaque
// command bytes, framed so that a damaged or foreign message is refused by
// name instead of being replayed into a document.
//
//   "TJ1" | version (u64 LE) | author length (u32 LE) | author | command bytes
//
// Version 0 is the genesis message written when the document is created: it
// gives the subject a last sequence, so every later append can be checked
// with Nats-Expected-Last-Subject-Sequence (a check nats.c only sends for a
// sequence above 0).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/util/status.h"

namespace tessera::cluster {

struct JournalMessage {
  uint64_t version = 0;
  std::string author;
  std::string bytes;
};

std::string encodeJournalMessage(uint64_t version, std::string_view author, std::string_view bytes);
// `where` names the message in errors, e.g. "document 7, stream sequence 41".
Expected<JournalMessage> decodeJournalMessage(std::string_view payload, std::string_view where);

}  // namespace tessera::cluster
