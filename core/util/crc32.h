// CRC-32 as zlib computes it (the checksum of the document file,
// docs/DOCUMENT_FORMAT.md, and of every region, docs/REGION_ENCODING.md).
#pragma once

#include <cstdint>
#include <string_view>

namespace tessera {

uint32_t crc32Of(std::string_view bytes);

}  // namespace tessera
