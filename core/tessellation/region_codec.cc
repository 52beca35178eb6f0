#include "core/tessellation/region_codec.h"

#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/quantization_utils.h>
#include <draco/mesh/mesh.h>
#include <zlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "core/hierarchy/ids.h"
#include "core/util/byte_io.h"

namespace tessera {
namespace {

constexpr char kMagic[4] = {'T', 'S', 'R', 'G'};
constexpr double kFloatRounding = 0x1p-24;  // unit roundoff of float32
constexpr int kMaxPositionBits = 24;        // float32 significand
constexpr int kMinNormalBits = 2;           // the octahedral square needs a centre
constexpr int kMaxNormalBits = 24;
constexpr int kMaxCompressionLevel = 10;
constexpr double kUnitTolerance = 1e-6;
// Draco's stream has no size field to check its counts against, so the
// decoder refuses more triangles than this per payload byte before Draco
// allocates for them. Typical regions take about 3 bytes per triangle; the
// most compressible input found, a planar regular grid on the lattice with
// every id equal (every prediction exact), reaches 283 triangles per byte at
// 522k triangles. encodeRegion applies the same bound, so whatever it
// produces decodes.
constexpr uint64_t kMaxTrianglesPerPayloadByte = 1024;
// ids.h packs a VertexId into 64 bits. Draco converts integer attributes to
// int32 and refuses values above INT32_MAX or value ranges of 2^31 and more
// (GeometryAttribute::ConvertComponentValue, PredictionSchemeWrapTransformBase::
// InitCorrectionBounds), and its rANS coder sorts a table as large as the
// largest symbol on every call. Eight 8-bit components keep every symbol
// below 512: on fandisk regions that encodes twice as fast as four 16-bit
// components, and smaller.
constexpr int kIdComponents = 8;
// The header's flags: bit 0 set = the regions of a display-only profile,
// with no vertex id attribute; bit 1 set = a profile with ids whose payload
// leaves them to the receiver's copy of the layout. Never both.
constexpr uint16_t kFlagNoVertexIds = 1;
constexpr uint16_t kFlagLayoutIds = 2;
// Bit 2: ids as points of the region's lattice (region_lattice.h), two
// bytes that Draco predicts from the neighbours instead of eight per id.
constexpr uint16_t kFlagLatticeIds = 4;
constexpr int kLatticeComponents = 2;

// How a payload carries vertex ids.
enum class IdCoding { kNone, kBytes, kLattice };

std::string num(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", x);
  return text;
}

std::string vecText(const Vec3& p) { return "(" + num(p[0]) + ", " + num(p[1]) + ", " + num(p[2]) + ")"; }

std::string hex32(uint32_t x) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08x", x);
  return text;
}

uint32_t crc32Of(const char* data, size_t size) {
  return static_cast<uint32_t>(::crc32(0L, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(size)));
}

bool isFloat32(double x) {
  return std::isfinite(x) && std::fabs(x) <= FLT_MAX && static_cast<double>(static_cast<float>(x)) == x;
}

// Nearest float32 at or below (above) x; x must be within float32 range.
double floatDown(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
double floatUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

uint32_t maxQuantized(int bits) { return (uint32_t{1} << bits) - 1; }

// The largest |coordinate| of the grid's corners: float32 rounding is
// relative to it.
double largestCoordinate(const QuantizationGrid& grid) {
  double m = 0.0;
  for (int k = 0; k < 3; ++k) m = std::max({m, std::fabs(grid.origin[k]), std::fabs(grid.origin[k] + grid.range)});
  return m;
}

// How far, in steps, float32 rounding can move the encoder's lattice index
// (value - origin) * (2^bits - 1) / range + 1/2 before Draco floors it
// (Quantizer in draco/core/quantization_utils.h): the conversion of the
// value to float errs by u M, the subtraction by u range, the reciprocal and
// the product by u each relative to the index, the + 1/2 by u 2^bits. In
// steps that is at most u 2^bits (M / range + 4); 5 leaves a margin.
double indexSlack(const QuantizationGrid& grid) {
  return kFloatRounding * std::ldexp(1.0, grid.positionBits) * (largestCoordinate(grid) / grid.range + 5.0);
}

// Under this slack the floored index of any point inside the grid stays in
// [0, 2^bits - 1], which Draco's coders assume (an index moves out only when
// the slack reaches half a step); the rest is margin.
constexpr double kMaxIndexSlack = 0.45;

}  // namespace

Status QuantizationGrid::check() const {
  for (int k = 0; k < 3; ++k) {
    if (!isFloat32(origin[k])) {
      return invalidArgument("quantization grid: origin " + vecText(origin) +
                             " is not made of finite float32 values (Draco stores it as float32; use gridFor)");
    }
  }
  if (!isFloat32(range) || range <= 0.0 || !(largestCoordinate(*this) < FLT_MAX / 2)) {
    return invalidArgument("quantization grid: range " + num(range) +
                           " must be a positive float32 value with origin + range within float32");
  }
  if (positionBits < 1 || positionBits > kMaxPositionBits) {
    return invalidArgument("quantization grid: positionBits " + std::to_string(positionBits) + " outside [1, " +
                           std::to_string(kMaxPositionBits) + "]");
  }
  if (normalBits < kMinNormalBits || normalBits > kMaxNormalBits) {
    return invalidArgument("quantization grid: normalBits " + std::to_string(normalBits) + " outside [" +
                           std::to_string(kMinNormalBits) + ", " + std::to_string(kMaxNormalBits) + "]");
  }
  if (indexSlack(*this) > kMaxIndexSlack) {
    return invalidArgument("quantization grid: " + std::to_string(positionBits) + " bits over a range of " +
                           num(range) + " at " + num(largestCoordinate(*this)) +
                           " from the origin are finer than float32 resolves there");
  }
  return Status::ok();
}

double QuantizationGrid::maxPositionError() const {
  const double step = range / maxQuantized(positionBits);
  // Encoding: half a step of rounding plus the index slack. Decoding
  // (Dequantizer, then + origin) errs by u 2 range for the product and u M for
  // the sum; 1.001 covers the second-order terms.
  const double decoding = 1.001 * kFloatRounding * (2.0 * range + largestCoordinate(*this));
  const double perAxis = step * (0.5 + indexSlack(*this)) + decoding;
  return std::sqrt(3.0) * perAxis;
}

Expected<QuantizationGrid> gridFor(const Vec3& bboxMin, const Vec3& bboxMax, double maxErrorFraction) {
  const std::string box = "bounding box " + vecText(bboxMin) + " .. " + vecText(bboxMax);
  if (!isFinite(bboxMin) || !isFinite(bboxMax)) return invalidArgument("gridFor: " + box + " is not finite");
  for (int k = 0; k < 3; ++k) {
    if (bboxMin[k] > bboxMax[k]) return invalidArgument("gridFor: " + box + " has min > max on axis " + std::to_string(k));
  }
  if (!(maxErrorFraction > 0.0 && maxErrorFraction < 1.0)) {
    return invalidArgument("gridFor: maxErrorFraction " + num(maxErrorFraction) + " outside (0, 1)");
  }
  const double diagonal = (bboxMax - bboxMin).norm();
  if (!(diagonal > 0.0)) return invalidArgument("gridFor: " + box + " is a single point: no size to relate an error to");
  const double pad = kGridPaddingFraction * diagonal;
  double magnitude = 0.0;
  for (int k = 0; k < 3; ++k) magnitude = std::max({magnitude, std::fabs(bboxMin[k]), std::fabs(bboxMax[k])});
  if (!(magnitude + 2.0 * diagonal < FLT_MAX / 4)) {
    return invalidArgument("gridFor: " + box + " exceeds the float32 range Draco stores positions in");
  }

  QuantizationGrid grid;
  grid.normalBits = kDefaultNormalBits;
  double extent = 0.0;
  for (int k = 0; k < 3; ++k) {
    grid.origin[k] = floatDown(bboxMin[k] - pad);
    extent = std::max(extent, bboxMax[k] + pad - grid.origin[k]);
  }
  grid.range = floatUp(extent);
  const double target = maxErrorFraction * diagonal;
  for (int bits = 1; bits <= kMaxPositionBits; ++bits) {
    grid.positionBits = bits;
    if (indexSlack(grid) <= kMaxIndexSlack && grid.maxPositionError() <= target) return grid;
  }
  return invalidArgument("gridFor: " + box + ": no position bits up to " + std::to_string(kMaxPositionBits) +
                         " reach an error of " + num(target) + ": the box is too far from the origin for its size " +
                         "to be quantized in float32");
}

namespace {

Status checkMesh(const RegionMesh& mesh, const QuantizationGrid& grid) {
  const size_t n = mesh.positions.size();
  if (mesh.triangles.empty()) return invalidMesh("no triangles (an emptied region is not encoded)");
  if (mesh.triangles.size() > kMaxRegionTriangles) {
    return invalidMesh(std::to_string(mesh.triangles.size()) + " triangles exceed the limit of " +
                       std::to_string(kMaxRegionTriangles));
  }
  if (mesh.normals.size() != n) {
    return invalidMesh(std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) + " positions");
  }
  if (mesh.vertexIds.size() != n) {
    return invalidMesh(std::to_string(mesh.vertexIds.size()) + " vertex ids for " + std::to_string(n) + " positions");
  }
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = mesh.positions[i];
    const auto vertex = [&] {
      return "vertex " + std::to_string(i) + " (" + VertexId::fromPacked(mesh.vertexIds[i]).toString() + ")";
    };
    if (!isFinite(p)) return invalidMesh(vertex() + ": position " + vecText(p) + " is not finite");
    if (!grid.contains(p)) {
      return invalidMesh(vertex() + ": position " + vecText(p) + " is outside the quantization grid " +
                         vecText(grid.origin) + " + [0, " + num(grid.range) + "]^3");
    }
    const Vec3& normal = mesh.normals[i];
    if (!isFinite(normal)) return invalidMesh(vertex() + ": normal " + vecText(normal) + " is not finite");
    if (std::fabs(normal.norm() - 1.0) > kUnitTolerance) {
      return invalidMesh(vertex() + ": normal " + vecText(normal) + " has length " + num(normal.norm()) + ", not 1");
    }
  }
  std::vector<char> used(n, 0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int c = 0; c < 3; ++c) {
      if (t[c] < 0 || static_cast<size_t>(t[c]) >= n) {
        return invalidMesh("triangle " + std::to_string(f) + ": index " + std::to_string(t[c]) + " outside [0, " +
                           std::to_string(n) + ")");
      }
      used[t[c]] = 1;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      return invalidMesh("triangle " + std::to_string(f) + " repeats a vertex (" + std::to_string(t[0]) + ", " +
                         std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")");
    }
  }
  const auto unused = std::find(used.begin(), used.end(), 0);
  if (unused != used.end()) {
    const size_t i = static_cast<size_t>(unused - used.begin());
    return invalidMesh("vertex " + std::to_string(i) + " (" + VertexId::fromPacked(mesh.vertexIds[i]).toString() +
                       ") is used by no triangle");
  }
  return Status::ok();
}

int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components, draco::DataType dataType,
                 int componentBytes, size_t count) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, static_cast<int8_t>(components), dataType, false, components * componentBytes, 0);
  return mesh.AddAttribute(attribute, /*identity_mapping=*/true, static_cast<uint32_t>(count));
}

// draco::Mesh is neither copyable nor movable, hence the unique_ptr.
Expected<std::unique_ptr<draco::Mesh>> buildDracoMesh(const RegionMesh& region, IdCoding coding,
                                                      const RegionLattice* lattice) {
  auto meshPtr = std::make_unique<draco::Mesh>();
  draco::Mesh& mesh = *meshPtr;
  const size_t n = region.positions.size();
  mesh.set_num_points(static_cast<uint32_t>(n));
  mesh.SetNumFaces(region.triangles.size());
  for (size_t f = 0; f < region.triangles.size(); ++f) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c) face[c] = draco::PointIndex(static_cast<uint32_t>(region.triangles[f][c]));
    mesh.SetFace(draco::FaceIndex(static_cast<uint32_t>(f)), face);
  }
  const int positionId = addAttribute(mesh, draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, 4, n);
  const int normalId = addAttribute(mesh, draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32, 4, n);
  const int idComponents = coding == IdCoding::kLattice ? kLatticeComponents : kIdComponents;
  const int idId = coding == IdCoding::kNone
                       ? 0
                       : addAttribute(mesh, draco::GeometryAttribute::GENERIC, idComponents, draco::DT_UINT8, 1, n);
  if (positionId < 0 || normalId < 0 || idId < 0) return internalError("Draco refused to add an attribute");
  for (size_t i = 0; i < n; ++i) {
    const draco::AttributeValueIndex index(static_cast<uint32_t>(i));
    const Vec3& p = region.positions[i];
    const float position[3] = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
    mesh.attribute(positionId)->SetAttributeValue(index, position);
    const Vec3 u = region.normals[i].normalized();
    const float normal[3] = {static_cast<float>(u[0]), static_cast<float>(u[1]), static_cast<float>(u[2])};
    mesh.attribute(normalId)->SetAttributeValue(index, normal);
    if (coding == IdCoding::kNone) continue;
    uint8_t id[kIdComponents];
    if (coding == IdCoding::kLattice) {
      const auto point = lattice->pointOf(VertexId::fromPacked(region.vertexIds[i]));
      if (!point) {
        return invalidMesh("vertex " + std::to_string(i) + " (" + VertexId::fromPacked(region.vertexIds[i]).toString() +
                           ") is not a vertex of the region's root face");
      }
      id[0] = static_cast<uint8_t>((*point)[0]);
      id[1] = static_cast<uint8_t>((*point)[1]);
    } else {
      for (int c = 0; c < kIdComponents; ++c) id[c] = static_cast<uint8_t>(region.vertexIds[i] >> (8 * c));
    }
    mesh.attribute(idId)->SetAttributeValue(index, id);
  }
  return meshPtr;
}

// Draco's Encoder hands the explicit origin and range to its quantizer as
// option text written by std::to_string (draco/core/options.h,
// Options::SetVector and SetFloat): six decimals, so an origin of
// -0.173205093 reaches the quantizer as -0.173205003 and a small range loses
// its digits. The header states the grid and decodeRegion checks Draco used
// exactly that, so the same two options are rewritten with nine significant
// digits, which round-trip every float32 (std::strtof and std::atof read
// them back).
Status setExplicitQuantization(draco::Encoder& encoder, const QuantizationGrid& grid) {
  const float origin[3] = {static_cast<float>(grid.origin[0]), static_cast<float>(grid.origin[1]),
                           static_cast<float>(grid.origin[2])};
  const float range = static_cast<float>(grid.range);
  encoder.SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, grid.positionBits, 3, origin, range);
  const draco::Options* options = encoder.options().FindAttributeOptions(draco::GeometryAttribute::POSITION);
  if (options == nullptr || !options->IsOptionSet("quantization_origin") ||
      !options->IsOptionSet("quantization_range")) {
    return internalError("Draco keeps the explicit quantization under unexpected option names");
  }
  draco::Options exact = *options;
  char text[128];
  std::snprintf(text, sizeof(text), "%.9g %.9g %.9g", origin[0], origin[1], origin[2]);
  exact.SetString("quantization_origin", text);
  std::snprintf(text, sizeof(text), "%.9g", range);
  exact.SetString("quantization_range", text);
  encoder.options().SetAttributeOptions(draco::GeometryAttribute::POSITION, exact);
  return Status::ok();
}

void writeHeader(ByteWriter& w, const RegionHeader& header, IdCoding coding, uint32_t triangles, uint32_t payloadBytes) {
  w.bytes().append(kMagic, sizeof(kMagic));
  w.put<uint16_t>(kRegionFormatVersion);
  w.put<uint16_t>(!header.profile.vertexIds ? kFlagNoVertexIds
                  : !header.idsInline       ? kFlagLayoutIds
                  : coding == IdCoding::kLattice ? kFlagLatticeIds
                                                 : 0);
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

Expected<std::string> encodeRegion(const RegionHeader& header, const RegionMesh& mesh, int compressionLevel) {
  const std::string where = "region " + std::to_string(header.regionId);
  TESSERA_RETURN_IF_ERROR(header.profile.check().withContext(where));
  TESSERA_RETURN_IF_ERROR(header.grid.check().withContext(where));
  if (compressionLevel < 0 || compressionLevel > kMaxCompressionLevel) {
    return invalidArgument(where + ": compression level " + std::to_string(compressionLevel) + " outside [0, " +
                           std::to_string(kMaxCompressionLevel) + "]");
  }
  if (header.layoutVersion > header.documentVersion) {
    return invalidArgument(where + ": layout version " + std::to_string(header.layoutVersion) +
                           " is later than the document version " + std::to_string(header.documentVersion));
  }
  if (!header.idsInline && !header.profile.vertexIds) {
    return invalidArgument(where + ": the layout's ids stand in for inline ids only in a profile with vertex ids");
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
  TESSERA_ASSIGN_OR_RETURN(const std::unique_ptr<draco::Mesh> dracoMesh,
                           buildDracoMesh(mesh, coding, lattice ? &*lattice : nullptr));

  draco::Encoder encoder;
  TESSERA_RETURN_IF_ERROR(setExplicitQuantization(encoder, header.grid).withContext(where));
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, header.grid.normalBits);
  // Ids are labels, not geometry: a parallelogram of ids predicts nothing,
  // while the difference from the previous vertex in Draco's traversal
  // follows the locality of the numbering (smaller and faster on fandisk
  // regions; docs/REGION_ENCODING.md).
  // Lattice points are coordinates on the mesh: a parallelogram of them
  // predicts the next exactly wherever the tessellation is regular.
  const draco::Status idPrediction = encoder.SetAttributePredictionScheme(
      draco::GeometryAttribute::GENERIC,
      coding == IdCoding::kLattice ? draco::MESH_PREDICTION_PARALLELOGRAM : draco::PREDICTION_DIFFERENCE);
  if (!idPrediction.ok()) return internalError(where + ": Draco refused the id prediction: " + idPrediction.error_msg_string());
  const int speed = kMaxCompressionLevel - compressionLevel;
  encoder.SetSpeedOptions(speed, speed);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*dracoMesh, &buffer);
  if (!status.ok()) return internalError(where + ": Draco encoding failed: " + status.error_msg_string());

  const uint64_t triangles = mesh.triangles.size();
  if (buffer.size() > kMaxRegionBytes - kRegionHeaderBytes - kRegionTrailerBytes ||
      triangles > kMaxTrianglesPerPayloadByte * buffer.size()) {
    return internalError(where + ": " + std::to_string(triangles) + " triangles in " + std::to_string(buffer.size()) +
                         " Draco bytes fall outside what decodeRegion accepts");
  }
  ByteWriter w;
  w.bytes().reserve(kRegionHeaderBytes + kMaxRegionFrameBytes + buffer.size() + kRegionTrailerBytes);
  writeHeader(w, header, coding, static_cast<uint32_t>(triangles), static_cast<uint32_t>(buffer.size()));
  w.bytes().append(buffer.data(), buffer.size());
  w.put<uint32_t>(crc32Of(w.bytes().data(), w.bytes().size()));
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
  if (fidelity > 1) return parseError(r.source() + ": LOD fidelity flag " + std::to_string(fidelity) + " is not 0 or 1");
  header.profile.fidelity = fidelity == 1;
  header.grid.positionBits = positionBits;
  header.grid.normalBits = normalBits;
  return Status::ok();
}

// Draco's varint (draco/core/varint_decoding.h): 7 bits a byte, low first,
// at most 5 bytes for 32 bits.
Status getVarint(ByteReader& r, uint32_t& value, const char* what) {
  uint64_t wide = 0;
  TESSERA_RETURN_IF_ERROR(r.getVarint(wide, 32, what));
  value = static_cast<uint32_t>(wide);
  return Status::ok();
}

// Reads the counts Draco will allocate for, from the start of its bitstream
// 2.2, before Draco sees the bytes: the header (DracoHeader in
// compression_shared.h), then for sequential coding the face and point counts
// (MeshSequentialDecoder::DecodeConnectivity), for Edgebreaker the traversal
// type, vertex and face counts, attribute data count, symbol and split symbol
// counts (MeshEdgebreakerDecoderImpl::DecodeConnectivity). Every count must be
// consistent with the header's triangle count, which the input size bounds.
Status checkDracoCounts(std::string_view payload, uint32_t triangles, const std::string& where) {
  ByteReader r(payload.data(), payload.size(), where + ": Draco payload");
  std::array<char, 5> magic{};
  uint8_t major = 0, minor = 0, geometry = 0, method = 0;
  uint16_t flags = 0;
  TESSERA_RETURN_IF_ERROR(r.get(magic, "the Draco magic"));
  if (std::memcmp(magic.data(), "DRACO", 5) != 0) return parseError(r.source() + ": no DRACO magic");
  TESSERA_RETURN_IF_ERROR(r.get(major, "the Draco version"));
  TESSERA_RETURN_IF_ERROR(r.get(minor, "the Draco version"));
  if (major != draco::kDracoMeshBitstreamVersionMajor || minor != draco::kDracoMeshBitstreamVersionMinor) {
    return parseError(r.source() + ": bitstream version " + std::to_string(major) + "." + std::to_string(minor) +
                      ", expected " + std::to_string(draco::kDracoMeshBitstreamVersionMajor) + "." +
                      std::to_string(draco::kDracoMeshBitstreamVersionMinor));
  }
  TESSERA_RETURN_IF_ERROR(r.get(geometry, "the Draco geometry type"));
  TESSERA_RETURN_IF_ERROR(r.get(method, "the Draco method"));
  TESSERA_RETURN_IF_ERROR(r.get(flags, "the Draco flags"));
  if (geometry != draco::TRIANGULAR_MESH) return parseError(r.source() + ": not a triangle mesh");
  if (flags != 0) return parseError(r.source() + ": unexpected flags " + std::to_string(flags) + " (metadata?)");

  uint32_t faces = 0, vertices = 0;
  if (method == draco::MESH_SEQUENTIAL_ENCODING) {
    TESSERA_RETURN_IF_ERROR(getVarint(r, faces, "the face count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, vertices, "the point count"));
  } else if (method == draco::MESH_EDGEBREAKER_ENCODING) {
    uint8_t traversal = 0, attributeData = 0;
    uint32_t symbols = 0, splitSymbols = 0;
    TESSERA_RETURN_IF_ERROR(r.get(traversal, "the Edgebreaker traversal type"));
    if (traversal != draco::MESH_EDGEBREAKER_STANDARD_ENCODING && traversal != draco::MESH_EDGEBREAKER_VALENCE_ENCODING) {
      return parseError(r.source() + ": unknown Edgebreaker traversal type " + std::to_string(traversal));
    }
    TESSERA_RETURN_IF_ERROR(getVarint(r, vertices, "the vertex count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, faces, "the face count"));
    TESSERA_RETURN_IF_ERROR(r.get(attributeData, "the attribute data count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, symbols, "the symbol count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, splitSymbols, "the split symbol count"));
    if (symbols > faces || splitSymbols > symbols || attributeData > 3) {
      return parseError(r.source() + ": inconsistent Edgebreaker counts (" + std::to_string(faces) + " faces, " +
                        std::to_string(symbols) + " symbols, " + std::to_string(splitSymbols) + " splits)");
    }
  } else {
    return parseError(r.source() + ": unknown mesh method " + std::to_string(method));
  }
  if (faces != triangles) {
    return parseError(r.source() + ": " + std::to_string(faces) + " faces, the header announces " +
                      std::to_string(triangles));
  }
  if (vertices > 3 * static_cast<uint64_t>(faces)) {
    return parseError(r.source() + ": " + std::to_string(vertices) + " vertices for " + std::to_string(faces) +
                      " faces (at most 3 per face)");
  }
  return Status::ok();
}

Expected<const draco::PointAttribute*> findAttribute(const draco::Mesh& mesh, draco::GeometryAttribute::Type type,
                                                     draco::DataType dataType, int components, const std::string& what) {
  const draco::PointAttribute* attribute = mesh.GetNamedAttribute(type);
  if (mesh.NumNamedAttributes(type) != 1 || attribute == nullptr) {
    return parseError(what + ": expected exactly one attribute");
  }
  if (attribute->data_type() != dataType || attribute->num_components() != components ||
      attribute->byte_stride() != static_cast<int64_t>(components * draco::DataTypeLength(dataType))) {
    return parseError(what + ": unexpected data type or component count");
  }
  return attribute;
}

Expected<RegionMesh> decodeDraco(std::string_view payload, const RegionHeader& header, uint32_t triangles,
                                 const RegionLattice* lattice, const std::string& where) {
  draco::DecoderBuffer buffer;
  buffer.Init(payload.data(), payload.size());
  draco::Decoder decoder;
  // Positions come back as lattice indices with their quantization
  // parameters, which are checked against the header and range-checked below.
  decoder.SetSkipAttributeTransform(draco::GeometryAttribute::POSITION);
  auto decodedOr = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decodedOr.ok()) return parseError(where + ": Draco rejected the payload: " + decodedOr.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decodedOr).value();
  const uint32_t points = mesh->num_points();
  const bool withIds = header.profile.vertexIds && header.idsInline;
  const int attributes = withIds ? 3 : 2;
  if (mesh->num_faces() != triangles || points > 3 * static_cast<uint64_t>(triangles) ||
      mesh->num_attributes() != attributes) {
    return parseError(where + ": Draco decoded " + std::to_string(mesh->num_faces()) + " faces, " +
                      std::to_string(points) + " points and " + std::to_string(mesh->num_attributes()) +
                      " attributes; expected " + std::to_string(triangles) + " faces, " + std::to_string(attributes) +
                      " attributes");
  }
  TESSERA_ASSIGN_OR_RETURN(const draco::PointAttribute* positions,
                           findAttribute(*mesh, draco::GeometryAttribute::POSITION, draco::DT_INT32, 3, where + ": POSITION"));
  TESSERA_ASSIGN_OR_RETURN(const draco::PointAttribute* normals,
                           findAttribute(*mesh, draco::GeometryAttribute::NORMAL, draco::DT_FLOAT32, 3, where + ": NORMAL"));
  const draco::PointAttribute* ids = nullptr;
  if (withIds) {
    TESSERA_ASSIGN_OR_RETURN(ids, findAttribute(*mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT8,
                                                lattice ? kLatticeComponents : kIdComponents, where + ": vertex ids"));
  }

  draco::AttributeQuantizationTransform quantization;
  const QuantizationGrid& grid = header.grid;
  if (!quantization.InitFromAttribute(*positions) || quantization.quantization_bits() != grid.positionBits ||
      quantization.range() != static_cast<float>(grid.range) ||
      quantization.min_value(0) != static_cast<float>(grid.origin[0]) ||
      quantization.min_value(1) != static_cast<float>(grid.origin[1]) ||
      quantization.min_value(2) != static_cast<float>(grid.origin[2])) {
    return parseError(where + ": Draco's position quantization differs from the header's grid");
  }
  const int32_t maxIndex = static_cast<int32_t>(maxQuantized(grid.positionBits));
  draco::Dequantizer dequantizer;
  if (!dequantizer.Init(quantization.range(), maxIndex)) return parseError(where + ": unusable quantization range");

  RegionMesh out;
  out.positions.resize(points);
  out.normals.resize(points);
  if (withIds) out.vertexIds.resize(points);
  for (draco::PointIndex p(0); p < points; ++p) {
    const auto point = [&p] { return "point " + std::to_string(p.value()); };
    const draco::AttributeValueIndex pi = positions->mapped_index(p), ni = normals->mapped_index(p),
                                     ii = withIds ? ids->mapped_index(p) : draco::AttributeValueIndex(0);
    if (pi.value() >= positions->size() || ni.value() >= normals->size() || (withIds && ii.value() >= ids->size())) {
      return parseError(where + ": " + point() + " maps to no attribute value");
    }
    int32_t q[3];
    positions->GetValue(pi, q);
    for (int k = 0; k < 3; ++k) {
      if (q[k] < 0 || q[k] > maxIndex) return parseError(where + ": " + point() + " lies outside the grid");
      // The same float operations as Draco's InverseTransformAttribute, so
      // the result is bit-identical to a plain Draco decode.
      const float value = dequantizer.DequantizeFloat(q[k]);
      out.positions[p.value()][k] = value + quantization.min_value(k);
    }
    float n[3];
    normals->GetValue(ni, n);
    const Vec3 normal(n[0], n[1], n[2]);
    if (!isFinite(normal) || !(normal.norm() > 0.5)) return parseError(where + ": " + point() + " has no unit normal");
    out.normals[p.value()] = normal.normalized();
    if (!withIds) continue;
    uint8_t id[kIdComponents];
    ids->GetValue(ii, id);
    if (lattice) {
      const auto at = lattice->idAt(id[0], id[1]);
      if (!at) {
        return parseError(where + ": " + point() + " has lattice point (" + std::to_string(id[0]) + ", " +
                          std::to_string(id[1]) + "), outside the root face's lattice of side " +
                          std::to_string(lattice->side()));
      }
      out.vertexIds[p.value()] = at->packed();
      continue;
    }
    uint64_t packed = 0;
    for (int c = 0; c < kIdComponents; ++c) packed |= static_cast<uint64_t>(id[c]) << (8 * c);
    out.vertexIds[p.value()] = packed;
  }
  out.triangles.resize(triangles);
  for (draco::FaceIndex f(0); f < triangles; ++f) {
    const draco::Mesh::Face& face = mesh->face(f);
    for (int c = 0; c < 3; ++c) {
      if (face[c].value() >= points) {
        return parseError(where + ": face " + std::to_string(f.value()) + " uses a point beyond " + std::to_string(points));
      }
      out.triangles[f.value()][c] = static_cast<int>(face[c].value());
    }
  }
  return out;
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
  if (std::memcmp(magic.data(), kMagic, sizeof(kMagic)) != 0) {
    uint32_t value = 0;
    std::memcpy(&value, magic.data(), sizeof(value));
    return parseError(source + ": not a Tessera region (magic " + hex32(value) + ", expected \"TSRG\")");
  }
  uint16_t version = 0, flags = 0;
  TESSERA_RETURN_IF_ERROR(r.get(version, "the format version"));
  if (version != kRegionFormatVersion) {
    return unsupported(source + ": format version " + std::to_string(version) + " is not supported (this build reads " +
                       std::to_string(kRegionFormatVersion) + ")");
  }
  TESSERA_RETURN_IF_ERROR(r.get(flags, "the flags"));
  if ((flags & ~(kFlagNoVertexIds | kFlagLayoutIds | kFlagLatticeIds)) != 0) {
    return parseError(source + ": unknown flags " + std::to_string(flags) +
                      " (bit 0, no vertex ids, bit 1, the layout's ids, and bit 2, lattice ids, are defined)");
  }
  if ((flags & (flags - 1)) != 0) {
    return parseError(source + ": flags " + std::to_string(flags) + " claim more than one way of carrying ids");
  }
  RegionHeader header;
  Counts counts;
  TESSERA_RETURN_IF_ERROR(readHeader(r, header, counts));
  header.profile.vertexIds = (flags & kFlagNoVertexIds) == 0;
  header.idsInline = (flags & kFlagLayoutIds) == 0;
  if (r.offset() != kRegionHeaderBytes) return internalError(source + ": header layout and kRegionHeaderBytes disagree");
  if ((flags & kFlagLatticeIds) != 0) {
    TESSERA_ASSIGN_OR_RETURN(header.frame, readFrame(r));
  }
  const size_t payloadAt = r.offset();
  const uint64_t expected = static_cast<uint64_t>(counts.payloadBytes) + kRegionTrailerBytes;
  if (r.remaining() < expected) {
    return parseError(source + ": truncated: the header announces " + std::to_string(counts.payloadBytes) +
                      " Draco bytes and a 4-byte checksum, " + std::to_string(r.remaining()) + " bytes follow");
  }
  if (r.remaining() > expected) {
    return parseError(source + ": " + std::to_string(r.remaining() - expected) + " trailing bytes after the checksum");
  }
  uint32_t stored = 0;
  std::memcpy(&stored, bytes.data() + bytes.size() - kRegionTrailerBytes, sizeof(stored));
  const uint32_t computed = crc32Of(bytes.data(), bytes.size() - kRegionTrailerBytes);
  if (stored != computed) {
    return parseError(source + ": checksum mismatch (stored " + hex32(stored) + ", computed " + hex32(computed) +
                      "): the bytes are corrupted");
  }

  const std::string where = "region " + std::to_string(header.regionId) + " (document version " +
                            std::to_string(header.documentVersion) + ")";
  // A field that passed the checksum yet fails a check was written by a
  // broken encoder: still malformed input, so a parse error.
  for (const Status& status : {header.profile.check(), header.grid.check()}) {
    if (!status.isOk()) return parseError(where + ": " + status.message());
  }
  if (header.layoutVersion > header.documentVersion) {
    return parseError(where + ": layout version " + std::to_string(header.layoutVersion) + " is later than the document's");
  }
  if (counts.triangles == 0 || counts.triangles > kMaxRegionTriangles ||
      counts.triangles > kMaxTrianglesPerPayloadByte * counts.payloadBytes) {
    return parseError(where + ": " + std::to_string(counts.triangles) + " triangles in " +
                      std::to_string(counts.payloadBytes) + " Draco bytes is outside the accepted bounds");
  }
  std::optional<RegionLattice> lattice;
  if (header.frame) {
    const int depth = latticeDepth(*header.frame, header.profile);
    if (header.frame->face != header.regionId || header.frame->forward > 7) {
      return parseError(where + ": the frame names region " + std::to_string(header.frame->face) + " with edge directions " +
                        std::to_string(header.frame->forward));
    }
    auto built = RegionLattice::build(*header.frame, depth);
    if (!built.isOk()) return parseError(where + ": " + built.status().message());
    lattice = std::move(*built);
  }
  const std::string_view payload = bytes.substr(payloadAt, counts.payloadBytes);
  TESSERA_RETURN_IF_ERROR(checkDracoCounts(payload, counts.triangles, where));
  TESSERA_ASSIGN_OR_RETURN(RegionMesh mesh, decodeDraco(payload, header, counts.triangles, lattice ? &*lattice : nullptr, where));
  return std::make_pair(std::move(header), std::move(mesh));
}

Status adoptLayoutIds(const RegionHeader& header, RegionMesh& decoded, const RegionMesh& held, uint64_t heldLayout) {
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
