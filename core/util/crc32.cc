#include "core/util/crc32.h"

#include <zlib.h>

namespace tessera {

uint32_t crc32Of(std::string_view bytes) {
  return static_cast<uint32_t>(
      ::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

}  // namespace tessera
