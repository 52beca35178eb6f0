#include "core/tessellation/region_codec.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "core/hierarchy/ids.h"
#include "core/tessellation/float_text.h"
#include "core/tessellation/region_draco.h"
#include "core/tessellation/region_meshopt.h"
#include "core/util/byte_io.h"
#include "core/util/crc32.h"
#include "core/util/hex.h"

namespace tessera {
namespace {

using region_detail::IdCoding;

constexpr char kMagic[4] = {'T', 'S', 'R', 'G'};
constexpr char kMeshoptMagic[4] = {'T', 'S', 'R', 'M'};
constexpr double kUnitTolerance = 1e-6;
// The header's flags: bit 0 set = the regions of a display-only profile,
// with no vertex id attribute; bit 1 set = a profile with ids whose payload
// leaves them to the receiver's copy of the layout. Never both.
constexpr uint16_t kFlagNoVertexIds = 1;
constexpr uint16_t kFlagLayoutIds = 2;
// Bit 2: ids as points of the region's lattice (region_lattice.h), two
// bytes that Draco predicts from the neighbours instead of eight per id.
// Bit 3: the same on a quad's lattice (a quad split's region).
constexpr uint16_t kFlagLatticeIds = 4;
constexpr uint16_t kFlagQuadLatticeIds = 8;

Status checkMesh(const RegionMesh& mesh, const QuantizationGrid& grid) {
  const size_t n = mesh.positions.size();
  if (mesh.triangles.empty()) return invalidMesh("no triangles (an emptied region is not encoded)");
  if (mesh.triangles.size() > kMaxRegionTriangles) {
    return invalidMesh(std::to_string(mesh.triangles.size()) + " triangles exceed the limit of " +
                       std::to_string(kMaxRegionTriangles));
  }
  if (mesh.normals.size() != n) {
    return invalidMesh(std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) +
                       " positions");
  }
  if (mesh.vertexIds.size() != n) {
    return invalidMesh(std::to_string(mesh.vertexIds.size()) + " vertex ids for " + std::to_string(n) +
                       " positions");
  }
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = mesh.positions[i];
    const auto vertex = [&] {
      return "vertex " + std::to_string(i) + " (" + VertexId::fromPacked(mesh.vertexIds[i]).toString() + ")";
    };
    if (!isFinite(p)) return invalidMesh(vertex() + ": position " + pointText(p) + " is not finite");
    if (!grid.contains(p)) {
      return invalidMesh(vertex() + ": position " + pointText(p) + " is outside the quantization grid " +
                         pointText(grid.origin) + " + [0, " + floatText(grid.range) + "]^3");
    }
    const Vec3& normal = mesh.normals[i];
    if (!isFinite(normal)) return invalidMesh(vertex() + ": normal " + pointText(normal) + " is not finite");
    if (std::fabs(normal.norm() - 1.0) > kUnitTolerance) {
      return invalidMesh(vertex() + ": normal " + pointText(normal) + " has length " +
                         floatText(normal.norm()) + ", not 1");
    }
  }
  std::vector<char> used(n, 0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int c = 0; c < 3; ++c) {
      if (t[c] < 0 || static_cast<size_t>(t[c]) >= n) {
        return invalidMesh("triangle " + std::to_string(f) + ": index " + std::to_string(t[c]) +
                           " outside [0, " + std::to_string(n) + ")");
      }
      used[t[c]] = 1;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      return invalidMesh("triangle " + std::to_string(f) + " repeats a vertex (" + std::to_string(t[0]) +
                         ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")");
    }
  }
  const auto unused = std::find(used.begin(), used.end(), 0);
  if (unused != used.end()) {
    const size_t i = static_cast<size_t>(unused - used.begin());
    return invalidMesh("vertex " + std::to_string(i) + " (" +
                       VertexId::fromPacked(mesh.vertexIds[i]).toString() + ") is used by no triangle");
  }
  return Status::ok();
}

void writeHeader(ByteWriter& w, const RegionHeader& header, IdCoding coding, uint32_t triangles,
                 uint32_t payloadBytes) {
  w.bytes().append(header.codec == RegionCodec::kMeshopt ? kMeshoptMagic : kMagic, sizeof(kMagic));
  w.put<uint16_t>(kRegionFormatVersion);
  w.put<uint16_t>(!header.profile.vertexIds      ? kFlagNoVertexIds
                  : !header.idsInline            ? kFlagLayoutIds
                  : coding != IdCoding::kLattice ? 0
                  : header.frame->sides == 4     ? kFlagQuadLatticeIds
                                                 : kFlagLatticeIds);
  w.put<uint64_t>(header.regionId);
  w.put<uint64_t>(header.documentVersion);
  w.put<uint64_t>(header.layoutVersion);
  w.put<int32_t>(header.profile.baseLevel);
  w.put<int32_t>(header.profile.maxLevel);
  w.put<double>(header.profile.angleThresholdDegrees);
  w.put<int64_t>(header.profile.triangleBudget);
  w.put<uint8_t>(header.profile.fidelity ? 1 : 0);
  for (int k = 0; k < 3; ++k) w.put<double>(header.grid.origin[k]);
  w.put<double>(header.grid.range);
  w.put<uint8_t>(static_cast<uint8_t>(header.grid.positionBits));
  w.put<uint8_t>(static_cast<uint8_t>(header.grid.normalBits));
  w.put<uint32_t>(triangles);
  w.put<uint32_t>(payloadBytes);
  if (coding == IdCoding::kLattice) writeFrame(w, *header.frame);
}

// The lattice depth of a frame under a profile: how far its deepest level
// lies below the root face.
int latticeDepth(const RegionFrame& frame, const LodProfile& profile) {
  return profile.maxLevel - FaceId::fromPacked(frame.face).level();
}

}  // namespace

const char* regionCodecName(RegionCodec codec) {
  return codec == RegionCodec::kMeshopt ? "meshopt" : "draco";
}

Expected<std::string> encodeRegion(const RegionHeader& header, const RegionMesh& mesh, int compressionLevel) {
  const std::string where = "region " + std::to_string(header.regionId);
  TESSERA_RETURN_IF_ERROR(header.profile.check().withContext(where));
  TESSERA_RETURN_IF_ERROR(header.grid.check().withContext(where));
  if (compressionLevel < 0 || compressionLevel > region_detail::kMaxCompressionLevel) {
    return invalidArgument(where + ": compression level " + std::to_string(compressionLevel) +
                           " outside [0, " + std::to_string(region_detail::kMaxCompressionLevel) + "]");
  }
  if (header.layoutVersion > header.documentVersion) {
    return invalidArgument(where + ": layout version " + std::to_string(header.layoutVersion) +
                           " is later than the document version " + std::to_string(header.documentVersion));
  }
  if (!header.idsInline && !header.profile.vertexIds) {
    return invalidArgument(where +
                           ": the layout's ids stand in for inline ids only in a profile with vertex ids");
  }
  TESSERA_RETURN_IF_ERROR(checkMesh(mesh, header.grid).withContext(where));
  IdCoding coding = header.profile.vertexIds && header.idsInline ? IdCoding::kBytes : IdCoding::kNone;
  std::optional<RegionLattice> lattice;
  if (coding == IdCoding::kBytes && header.frame) {
    if (header.frame->face != header.regionId) {
      return invalidArgument(where + ": the frame is that of region " + std::to_string(header.frame->face));
    }
    const int depth = latticeDepth(*header.frame, header.profile);
    if (depth >= 0 && depth <= kMaxLatticeDepth) {
      auto built = RegionLattice::build(*header.frame, depth);
      if (!built.isOk()) return built.status().withContext(where);
      lattice = std::move(*built);
      coding = IdCoding::kLattice;
    }
  }
  const RegionLattice* latticeOrNull = lattice ? &*lattice : nullptr;
  TESSERA_ASSIGN_OR_RETURN(
      const std::string payload,
      header.codec == RegionCodec::kMeshopt
          ? region_detail::encodeMeshoptPayload(mesh, coding, latticeOrNull, header.grid, where)
          : region_detail::encodeDracoPayload(mesh, coding, latticeOrNull, header.grid, compressionLevel,
                                              where));

  const uint64_t triangles = mesh.triangles.size();
  if (payload.size() > kMaxRegionBytes - kRegionHeaderBytes - kRegionTrailerBytes ||
      triangles > region_detail::kMaxTrianglesPerPayloadByte * payload.size()) {
    return internalError(where + ": " + std::to_string(triangles) + " triangles in " +
                         std::to_string(payload.size()) +
                         " Draco bytes fall outside what decodeRegion accepts");
  }
  ByteWriter w;
  w.bytes().reserve(kRegionHeaderBytes + kMaxRegionFrameBytes + payload.size() + kRegionTrailerBytes);
  writeHeader(w, header, coding, static_cast<uint32_t>(triangles), static_cast<uint32_t>(payload.size()));
  w.bytes().append(payload);
  w.put<uint32_t>(crc32Of(w.bytes()));
  return std::move(w.bytes());
}

namespace {

struct Counts {
  uint32_t triangles = 0;
  uint32_t payloadBytes = 0;
};

Status readHeader(ByteReader& r, RegionHeader& header, Counts& counts) {
  uint8_t fidelity = 0, positionBits = 0, normalBits = 0;
  TESSERA_RETURN_IF_ERROR(r.get(header.regionId, "the region id"));
  TESSERA_RETURN_IF_ERROR(r.get(header.documentVersion, "the document version"));
  TESSERA_RETURN_IF_ERROR(r.get(header.layoutVersion, "the layout version"));
  int32_t baseLevel = 0, maxLevel = 0;
  TESSERA_RETURN_IF_ERROR(r.get(baseLevel, "the LOD base level"));
  TESSERA_RETURN_IF_ERROR(r.get(maxLevel, "the LOD max level"));
  header.profile.baseLevel = baseLevel;
  header.profile.maxLevel = maxLevel;
  TESSERA_RETURN_IF_ERROR(r.get(header.profile.angleThresholdDegrees, "the LOD angle threshold"));
  TESSERA_RETURN_IF_ERROR(r.get(header.profile.triangleBudget, "the LOD triangle budget"));
  TESSERA_RETURN_IF_ERROR(r.get(fidelity, "the LOD fidelity flag"));
  for (int k = 0; k < 3; ++k) TESSERA_RETURN_IF_ERROR(r.get(header.grid.origin[k], "the grid origin"));
  TESSERA_RETURN_IF_ERROR(r.get(header.grid.range, "the grid range"));
  TESSERA_RETURN_IF_ERROR(r.get(positionBits, "the position bits"));
  TESSERA_RETURN_IF_ERROR(r.get(normalBits, "the normal bits"));
  TESSERA_RETURN_IF_ERROR(r.get(counts.triangles, "the triangle count"));
  TESSERA_RETURN_IF_ERROR(r.get(counts.payloadBytes, "the Draco payload size"));
  if (fidelity > 1)
    return parseError(r.source() + ": LOD fidelity flag " + std::to_string(fidelity) + " is not 0 or 1");
  header.profile.fidelity = fidelity == 1;
  header.grid.positionBits = positionBits;
  header.grid.normalBits = normalBits;
  return Status::ok();
}

}  // namespace

Expected<std::pair<RegionHeader, RegionMesh>> decodeRegion(std::string_view bytes) {
  const std::string source = "region encoding";
  if (bytes.size() > kMaxRegionBytes) {
    return parseError(source + ": " + std::to_string(bytes.size()) + " bytes exceed the limit of " +
                      std::to_string(kMaxRegionBytes));
  }
  ByteReader r(bytes.data(), bytes.size(), source);
  std::array<char, 4> magic{};
  TESSERA_RETURN_IF_ERROR(r.get(magic, "the magic"));
  const bool meshopt = std::memcmp(magic.data(), kMeshoptMagic, sizeof(kMagic)) == 0;
  if (!meshopt && std::memcmp(magic.data(), kMagic, sizeof(kMagic)) != 0) {
    uint32_t value = 0;
    std::memcpy(&value, magic.data(), sizeof(value));
    return parseError(source + ": not a Tessera region (magic " + hexNumber(value, 8) +
                      ", expected \"TSRG\" or \"TSRM\")");
  }
  uint16_t version = 0, flags = 0;
  TESSERA_RETURN_IF_ERROR(r.get(version, "the format version"));
  if (version != kRegionFormatVersion) {
    return unsupported(source + ": format version " + std::to_string(version) +
                       " is not supported (this build reads " + std::to_string(kRegionFormatVersion) + ")");
  }
  TESSERA_RETURN_IF_ERROR(r.get(flags, "the flags"));
  if ((flags & ~(kFlagNoVertexIds | kFlagLayoutIds | kFlagLatticeIds | kFlagQuadLatticeIds)) != 0) {
    return parseError(source + ": unknown flags " + std::to_string(flags) +
                      " (bit 0, no vertex ids, bit 1, the layout's ids, bit 2, lattice ids, and bit 3, "
                      "quad lattice ids, are defined)");
  }
  if ((flags & (flags - 1)) != 0) {
    return parseError(source + ": flags " + std::to_string(flags) +
                      " claim more than one way of carrying ids");
  }
  RegionHeader header;
  header.codec = meshopt ? RegionCodec::kMeshopt : RegionCodec::kDraco;
  Counts counts;
  TESSERA_RETURN_IF_ERROR(readHeader(r, header, counts));
  header.profile.vertexIds = (flags & kFlagNoVertexIds) == 0;
  header.idsInline = (flags & kFlagLayoutIds) == 0;
  if (r.offset() != kRegionHeaderBytes)
    return internalError(source + ": header layout and kRegionHeaderBytes disagree");
  if ((flags & (kFlagLatticeIds | kFlagQuadLatticeIds)) != 0) {
    TESSERA_ASSIGN_OR_RETURN(header.frame, readFrame(r, (flags & kFlagQuadLatticeIds) != 0 ? 4 : 3));
  }
  const size_t payloadAt = r.offset();
  const uint64_t expected = static_cast<uint64_t>(counts.payloadBytes) + kRegionTrailerBytes;
  if (r.remaining() < expected) {
    return parseError(source + ": truncated: the header announces " + std::to_string(counts.payloadBytes) +
                      " Draco bytes and a 4-byte checksum, " + std::to_string(r.remaining()) +
                      " bytes follow");
  }
  if (r.remaining() > expected) {
    return parseError(source + ": " + std::to_string(r.remaining() - expected) +
                      " trailing bytes after the checksum");
  }
  uint32_t stored = 0;
  std::memcpy(&stored, bytes.data() + bytes.size() - kRegionTrailerBytes, sizeof(stored));
  const uint32_t computed = crc32Of(bytes.substr(0, bytes.size() - kRegionTrailerBytes));
  if (stored != computed) {
    return parseError(source + ": checksum mismatch (stored " + hexNumber(stored, 8) + ", computed " +
                      hexNumber(computed, 8) + "): the bytes are corrupted");
  }

  const std::string where = "region " + std::to_string(header.regionId) + " (document version " +
                            std::to_string(header.documentVersion) + ")";
  // A field that passed the checksum yet fails a check was written by a
  // broken encoder: still malformed input, so a parse error.
  for (const Status& status : {header.profile.check(), header.grid.check()}) {
    if (!status.isOk()) return parseError(where + ": " + status.message());
  }
  if (header.layoutVersion > header.documentVersion) {
    return parseError(where + ": layout version " + std::to_string(header.layoutVersion) +
                      " is later than the document's");
  }
  if (counts.triangles == 0 || counts.triangles > kMaxRegionTriangles ||
      counts.triangles > region_detail::kMaxTrianglesPerPayloadByte * counts.payloadBytes) {
    return parseError(where + ": " + std::to_string(counts.triangles) + " triangles in " +
                      std::to_string(counts.payloadBytes) + " Draco bytes is outside the accepted bounds");
  }
  std::optional<RegionLattice> lattice;
  if (header.frame) {
    const int depth = latticeDepth(*header.frame, header.profile);
    if (header.frame->face != header.regionId) {
      return parseError(where + ": the frame names region " + std::to_string(header.frame->face));
    }
    auto built = RegionLattice::build(*header.frame, depth);
    if (!built.isOk()) return parseError(where + ": " + built.status().message());
    lattice = std::move(*built);
  }
  const std::string_view payload = bytes.substr(payloadAt, counts.payloadBytes);
  const bool withIds = header.profile.vertexIds && header.idsInline;
  if (meshopt) {
    TESSERA_ASSIGN_OR_RETURN(
        RegionMesh mesh, region_detail::decodeMeshoptPayload(payload, header.grid, withIds, counts.triangles,
                                                             lattice ? &*lattice : nullptr, where));
    return std::make_pair(std::move(header), std::move(mesh));
  }
  TESSERA_RETURN_IF_ERROR(region_detail::checkDracoCounts(payload, counts.triangles, where));
  TESSERA_ASSIGN_OR_RETURN(RegionMesh mesh,
                           region_detail::decodeDracoPayload(payload, header.grid, withIds, counts.triangles,
                                                             lattice ? &*lattice : nullptr, where));
  return std::make_pair(std::move(header), std::move(mesh));
}

Status adoptLayoutIds(const RegionHeader& header, RegionMesh& decoded, const RegionMesh& held,
                      uint64_t heldLayout) {
  const std::string where = "region " + std::to_string(header.regionId) + " (document version " +
                            std::to_string(header.documentVersion) + ")";
  if (header.idsInline || !header.profile.vertexIds) {
    return invalidArgument(where + ": the payload has no layout ids to adopt");
  }
  if (heldLayout != header.layoutVersion) {
    return invalidArgument(where + ": its ids are those of layout " + std::to_string(header.layoutVersion) +
                           ", the receiver holds layout " + std::to_string(heldLayout));
  }
  // Equal decoded triangles mean Draco decoded the same connectivity in the
  // same order, so vertex k is the held vertex k.
  if (held.triangles != decoded.triangles || held.vertexIds.size() != decoded.positions.size()) {
    return invalidArgument(where + ": its triangles differ from those of the held layout " +
                           std::to_string(heldLayout));
  }
  decoded.vertexIds = held.vertexIds;
  return Status::ok();
}

}  // namespace tessera
