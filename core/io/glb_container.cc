#include "core/io/glb_container.h"

#include <cstdint>
#include <cstring>

namespace tessera::io_detail {

uint32_t glbU32At(std::string_view data, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, data.data() + at, sizeof v);
  return v;  // little-endian, as the format and every supported host
}

Status checkGlbContainer(std::string_view data, const std::string& name) {
  const std::string what = name + ": malformed glTF: GLB container: ";
  if (data.size() < kGlbHeaderBytes + kGlbChunkHeaderBytes)
    return parseError(what + std::to_string(data.size()) +
                      " bytes, shorter than a header and one chunk header");
  if (glbU32At(data, 0) != kGlbMagic) return parseError(what + "it does not begin with \"glTF\"");
  if (const uint32_t version = glbU32At(data, 4); version != 2)
    return parseError(what + "version " + std::to_string(version) + ", only version 2 is read");
  const uint64_t length = glbU32At(data, 8);
  if (length != data.size())
    return parseError(what + "the header's length " + std::to_string(length) + " is not the file's " +
                      std::to_string(data.size()) + " bytes");
  uint64_t at = kGlbHeaderBytes;
  for (int chunk = 0; at < length; ++chunk) {
    const std::string where = "chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
    if (at + kGlbChunkHeaderBytes > length)
      return parseError(what + where + ": its header runs past the end");
    const uint64_t bytes = glbU32At(data, at);
    const uint32_t type = glbU32At(data, at + 4);
    if (chunk == 0 && type != kGlbJsonChunk)
      return parseError(what + where + ": the first chunk is not JSON");
    if (bytes % 4 != 0)
      return parseError(what + where + ": a length of " + std::to_string(bytes) +
                        " bytes, not a multiple of 4");
    if (at + kGlbChunkHeaderBytes + bytes > length)
      return parseError(what + where + ": its " + std::to_string(bytes) + " bytes run past the end");
    at += kGlbChunkHeaderBytes + bytes;
  }
  return Status::ok();
}

}  // namespace tessera::io_detail
