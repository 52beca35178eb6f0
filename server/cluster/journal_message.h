// The payload of one journal message on a document's JetStream subject
// (tessera.journal.<id>): the entry's version, its author, the client
// command it came from and the opaque command bytes, framed so that a
// damaged or foreign message is refused by name instead of being replayed
// into a document.
//
//   "TJ2" | kind (u8) | version (u64 LE) | author length (u32 LE) | author
//         | author session (u64 LE) | client_seq (u64 LE) | command bytes
//
// kind 0 is a journal entry. kind 1 is a fence: no version of its own (it
// repeats the last one its writer loaded, so it is a lower bound: a write
// that had timed out may land just before it); the genesis message written
// at creation is one (version 0), and so is the message a new owner writes
// after loading the document. A fence gives the subject a new last
// sequence, so every append checked with Nats-Expected-Last-Subject-Sequence
// by a writer that has not seen it fails (nats.c sends that check only for
// a sequence above 0).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/util/status.h"

namespace tessera::cluster {

struct JournalMessage {
  bool fence = false;
  uint64_t version = 0;
  std::string author{};
  uint64_t authorSession = 0, clientSeq = 0;
  std::string bytes{};
};

std::string encodeJournalMessage(const JournalMessage& message);
// `where` names the message in errors, e.g. "document 7, stream sequence 41".
Expected<JournalMessage> decodeJournalMessage(std::string_view payload, std::string_view where);

}  // namespace tessera::cluster
