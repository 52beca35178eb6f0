// The region decoder (core/tessellation/region_codec.h) on untrusted bytes:
// what a viewer does with every region a server (or anyone on the path)
// sends it.
//
// Each input is decoded as is, then with its CRC-32 trailer recomputed: the
// first exercises the header and checksum checks, the second lets mutations
// reach the frame, the Draco payload and the checks after it (libFuzzer
// rarely forges a CRC). A decoded region must be consistent (one normal and
// none or one id per position, triangle corners in range), and when it
// re-encodes under its own header, that encoding must decode again with the
// same header and triangle count.
#include <zlib.h>

#include <cstring>
#include <string>

#include "core/tessellation/region_codec.h"
#include "fuzz_support.h"

namespace tessera::fuzz {
namespace {

void decodeOne(const std::string& bytes) {
  auto decoded = decodeRegion(bytes);
  if (!decoded.isOk()) {
    checkError(decoded.status(), "decodeRegion");
    return;
  }
  const auto& [header, mesh] = *decoded;
  const size_t n = mesh.positions.size();
  require(mesh.normals.size() == n, "a decoded region has not one normal per position");
  require(mesh.vertexIds.empty() || mesh.vertexIds.size() == n,
          "a decoded region has not one id per position");
  require(!mesh.triangles.empty(), "a decoded region has no triangle");
  for (const auto& t : mesh.triangles) {
    for (int c : t)
      require(c >= 0 && static_cast<size_t>(c) < n, "a decoded triangle corner is out of range");
  }
  if (!header.idsInline || (header.profile.vertexIds && mesh.vertexIds.empty())) return;
  auto again = encodeRegion(header, mesh);
  if (!again.isOk()) {
    // The decoded floats may sit a rounding outside the rules the encoder
    // checks (unit normals, the grid); that refusal is the encoder's to make.
    checkError(again.status(), "encodeRegion of a decoded region");
    return;
  }
  auto redecoded = decodeRegion(*again);
  if (!redecoded.isOk()) fail("a re-encoded region does not decode: " + redecoded.status().toString());
  require(redecoded->first == header, "a re-encoded region decodes with another header");
  require(redecoded->second.triangles.size() == mesh.triangles.size(),
          "a re-encoded region decodes with another triangle count");
}

}  // namespace
}  // namespace tessera::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  std::string bytes = fuzz::bytesOf(data, size);
  fuzz::decodeOne(bytes);
  if (bytes.size() > kRegionTrailerBytes) {
    const uint32_t crc =
        static_cast<uint32_t>(::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()),
                                      static_cast<uInt>(bytes.size() - kRegionTrailerBytes)));
    if (std::memcmp(bytes.data() + bytes.size() - kRegionTrailerBytes, &crc, sizeof(crc)) != 0) {
      std::memcpy(bytes.data() + bytes.size() - kRegionTrailerBytes, &crc, sizeof(crc));
      fuzz::decodeOne(bytes);
    }
  }
  return 0;
}
