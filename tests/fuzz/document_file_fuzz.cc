// The document file reader (core/document/document_file.h) behind the
// morph container (core/morph/keyed_document_file.h): what `tessera doc`
// and the server's snapshots read back from disk.
//
// Each input is read as is, then with its header's payload size and its
// CRC-32 trailer made to match the bytes (when it starts with the magic), so
// mutations reach the payload: options, base mesh, edits, and
// Document::restore validating every edit. A document that reads must
// serialize to bytes that read again and serialize identically.
#include <zlib.h>

#include <cstring>
#include <string>

#include "core/morph/keyed_document_file.h"
#include "fuzz_support.h"

namespace tessera::fuzz {
namespace {

constexpr size_t kMagicBytes = 8;
constexpr size_t kHeaderBytes = kMagicBytes + 4 + 4 + 8;  // magic, version, reserved, payload size
constexpr size_t kTrailerBytes = 4;

void readOne(const std::string& bytes) {
  auto doc = deserializeKeyedDocument(bytes, "fuzz.tsd");
  if (!doc.isOk()) {
    checkError(doc.status(), "deserializeKeyedDocument");
    return;
  }
  const std::string written = serializeKeyedDocument(*doc);
  auto again = deserializeKeyedDocument(written, "rewritten.tsd");
  if (!again.isOk())
    fail("a document that read does not read back after saving: " + again.status().toString());
  require(serializeKeyedDocument(*again) == written, "saving a document twice gives different bytes");
}

}  // namespace
}  // namespace tessera::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera::fuzz;
  std::string bytes = bytesOf(data, size);
  readOne(bytes);
  if (bytes.size() >= kHeaderBytes + kTrailerBytes && bytes.compare(0, kMagicBytes, "TSRDOC\r\n") == 0) {
    const uint64_t payload = bytes.size() - kHeaderBytes - kTrailerBytes;
    const uint32_t crc = static_cast<uint32_t>(
        ::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + kHeaderBytes), static_cast<uInt>(payload)));
    std::string repaired = bytes;
    std::memcpy(repaired.data() + kHeaderBytes - 8, &payload,
                sizeof(payload));  // little-endian, as the format
    std::memcpy(repaired.data() + repaired.size() - kTrailerBytes, &crc, sizeof(crc));
    if (repaired != bytes) readOne(repaired);
  }
  return 0;
}
