#include "core/morph/keyed_document_file.h"

#include <cstring>

#include "core/document/document_file.h"
#include "core/util/byte_io.h"

namespace tessera {

namespace {

// Distinct from the document file's "TSRDOC\r\n", so either form is told
// apart by its first eight bytes; the CR LF reveals text-mode mangling.
constexpr char kMagic[8] = {'T', 'S', 'R', 'M', 'R', 'P', '\r', '\n'};
constexpr uint32_t kContainerVersion = 1;

void putBlob(ByteWriter& w, const std::string& bytes) {
  w.put<uint64_t>(bytes.size());
  w.putBytes(bytes);
}

Status getBlob(ByteReader& r, const char* what, std::string& out) {
  uint64_t size = 0;
  TESSERA_RETURN_IF_ERROR(r.get(size, what));
  if (size > r.remaining()) {
    return parseError(r.source() + ": " + what + " of " + std::to_string(size) +
                      " bytes exceeds the remaining " + std::to_string(r.remaining()));
  }
  return r.getBytes(out, static_cast<size_t>(size), what);
}

}  // namespace

std::string serializeKeyedDocument(const KeyedDocument& document) {
  if (!document.isMorph()) return serializeDocument(document.key0());
  ByteWriter w;
  w.putBytes(std::string(kMagic, sizeof(kMagic)));
  w.put<uint32_t>(kContainerVersion);
  w.put<uint32_t>(static_cast<uint32_t>(document.numKeys()));
  for (size_t k = 0; k < document.numKeys(); ++k) putBlob(w, serializeDocument(document.key(k)));
  putBlob(w, document.images().from);
  putBlob(w, document.images().to);
  return std::move(w.bytes());
}

Expected<KeyedDocument> deserializeKeyedDocument(const std::string& bytes, const std::string& source) {
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    TESSERA_ASSIGN_OR_RETURN(Document doc, deserializeDocument(bytes, source));
    return KeyedDocument(std::move(doc));
  }
  ByteReader r(bytes.data() + sizeof(kMagic), bytes.size() - sizeof(kMagic), source);
  uint32_t version = 0, keys = 0;
  TESSERA_RETURN_IF_ERROR(r.get(version, "the morph container version"));
  if (version != kContainerVersion) {
    return parseError(source + ": morph container version " + std::to_string(version) +
                      ", this build reads " + std::to_string(kContainerVersion));
  }
  TESSERA_RETURN_IF_ERROR(r.get(keys, "the key count"));
  if (keys != kMaxMorphKeys) {
    return parseError(source + ": a morph container of " + std::to_string(keys) +
                      " keys (it holds exactly 2)");
  }
  std::string key0, key1;
  MorphImages images;
  TESSERA_RETURN_IF_ERROR(getBlob(r, "key 0", key0));
  TESSERA_RETURN_IF_ERROR(getBlob(r, "key 1", key1));
  TESSERA_RETURN_IF_ERROR(getBlob(r, "the first image", images.from));
  TESSERA_RETURN_IF_ERROR(getBlob(r, "the second image", images.to));
  if (r.remaining() != 0) return parseError(source + ": trailing bytes after the morph container");
  TESSERA_ASSIGN_OR_RETURN(Document first, deserializeDocument(key0, source + " key 0"));
  TESSERA_ASSIGN_OR_RETURN(Document second, deserializeDocument(key1, source + " key 1"));
  KeyedDocument doc(std::move(first));
  TESSERA_RETURN_IF_ERROR(doc.restoreKey(std::move(second), std::move(images)).withContext(source));
  return doc;
}

}  // namespace tessera
