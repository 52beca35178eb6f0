// The journal entry decoder (server/journal_entry.h) and the replay of what
// it decodes: what the server does with its journal when it reopens a
// document after a crash.
//
// Input: a journal, as entries each prefixed by one length byte (at most
// 16 entries). Every entry is decoded; one that decodes must re-encode to
// bytes that decode to the same encoding, and is then applied, in order, to
// a creased-cube document of max level kFuzzDocumentLevel as recovery would
// (errors are fine: a damaged journal is refused, not crashed on); entries
// may add a morph key and edit it.
#include <string>

#include "fuzz_support.h"
#include "server/document/journal_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  using namespace tessera::fuzz;
  KeyedDocument doc(cubeDocument(kFuzzDocumentLevel));
  size_t at = 0;
  for (int entries = 0; entries < 16 && at < size; ++entries) {
    const size_t length = std::min<size_t>(data[at], size - at - 1);
    const std::string bytes = bytesOf(data + at + 1, length);
    at += 1 + length;
    auto entry = server::decodeJournalEntry(bytes, "journal entry " + std::to_string(entries));
    if (!entry.isOk()) {
      checkError(entry.status(), "decodeJournalEntry");
      continue;
    }
    const std::string encoded = server::encodeJournalEntry(*entry);
    auto again = server::decodeJournalEntry(encoded, "re-encoded entry");
    if (!again.isOk())
      fail("a decoded journal entry does not decode after re-encoding: " + again.status().toString());
    require(server::encodeJournalEntry(*again) == encoded, "a journal entry re-encodes differently");
    checkError(server::applyJournalEntry(doc, *entry), "applyJournalEntry");
  }
  return 0;
}
