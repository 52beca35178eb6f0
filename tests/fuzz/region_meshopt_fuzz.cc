// The meshopt region decoder (core/tessellation/region_meshopt.h, behind
// decodeRegion) on untrusted bytes: what a viewer subscribed with
// REGION_CODEC_MESHOPT does with every "TSRM" region it is sent
// (docs/REGION_ENCODING.md, "meshopt regions").
//
// Each input is decoded as is, then with its magic set to "TSRM" and its
// CRC-32 trailer recomputed: the first exercises the header and checksum
// checks, the second lets mutations reach the frame, the payload's prefix
// (vertex count, vertex buffer size), meshoptimizer's two streams and the
// checks on the decoded vertices and triangles (libFuzzer rarely forges a
// CRC). Forcing the magic keeps the second decode on this codec: a mutated
// magic would otherwise hand it to the Draco decoder, which region_decoder
// fuzzes. A decoded region must be consistent (one unit normal and none or
// one id per position, triangle corners in range and distinct, every vertex
// used, as encodeRegion requires), and when it re-encodes under its own
// header, that encoding must decode again with the same header and triangle
// count.
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

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
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k)
      require(std::isfinite(mesh.positions[i][k]), "a decoded position is not finite");
    require(std::fabs(mesh.normals[i].norm() - 1.0) < 1e-6, "a decoded normal is not of unit length");
  }
  for (const auto& t : mesh.triangles) {
    for (int c : t)
      require(c >= 0 && static_cast<size_t>(c) < n, "a decoded triangle corner is out of range");
    require(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], "a decoded triangle repeats a corner");
  }
  if (header.codec != RegionCodec::kMeshopt) return;  // the as-is decode of a Draco region
  // encodeRegion refuses a vertex no triangle uses, so no encoder writes
  // one: a decoded region must not hold one either.
  std::vector<bool> used(n, false);
  for (const auto& t : mesh.triangles)
    for (int c : t) used[static_cast<size_t>(c)] = true;
  for (size_t i = 0; i < n; ++i) require(used[i], "a decoded meshopt region has a vertex no triangle uses");
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
  if (bytes.size() > 4 + kRegionTrailerBytes) {
    const std::string original = bytes;
    std::memcpy(bytes.data(), "TSRM", 4);
    const uint32_t crc =
        static_cast<uint32_t>(::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()),
                                      static_cast<uInt>(bytes.size() - kRegionTrailerBytes)));
    std::memcpy(bytes.data() + bytes.size() - kRegionTrailerBytes, &crc, sizeof(crc));
    if (bytes != original) fuzz::decodeOne(bytes);
  }
  return 0;
}
