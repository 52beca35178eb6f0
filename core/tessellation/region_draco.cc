#include "core/tessellation/region_draco.h"

#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/quantization_utils.h>
#include <draco/mesh/mesh.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/hierarchy/ids.h"
#include "core/util/byte_io.h"

namespace tessera::region_detail {
namespace {

// ids.h packs a VertexId into 64 bits. Draco converts integer attributes to
// int32 and refuses values above INT32_MAX or value ranges of 2^31 and more
// (GeometryAttribute::ConvertComponentValue, PredictionSchemeWrapTransformBase::
// InitCorrectionBounds), and its rANS coder sorts a table as large as the
// largest symbol on every call. Eight 8-bit components keep every symbol
// below 512: on fandisk regions that encodes twice as fast as four 16-bit
// components, and smaller.
constexpr int kIdComponents = 8;
// Lattice ids (region_lattice.h): two bytes that Draco predicts from the
// neighbours instead of eight per id.
constexpr int kLatticeComponents = 2;

int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components,
                 draco::DataType dataType, int componentBytes, size_t count) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, static_cast<int8_t>(components), dataType, false, components * componentBytes,
                 0);
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
  const int idId = coding == IdCoding::kNone ? 0
                                             : addAttribute(mesh, draco::GeometryAttribute::GENERIC,
                                                            idComponents, draco::DT_UINT8, 1, n);
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
        return invalidMesh("vertex " + std::to_string(i) + " (" +
                           VertexId::fromPacked(region.vertexIds[i]).toString() +
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
  encoder.SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, grid.positionBits, 3, origin,
                                           range);
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

// Draco's varint (draco/core/varint_decoding.h): 7 bits a byte, low first,
// at most 5 bytes for 32 bits.
Status getVarint(ByteReader& r, uint32_t& value, const char* what) {
  uint64_t wide = 0;
  TESSERA_RETURN_IF_ERROR(r.getVarint(wide, 32, what));
  value = static_cast<uint32_t>(wide);
  return Status::ok();
}

Expected<const draco::PointAttribute*> findAttribute(const draco::Mesh& mesh,
                                                     draco::GeometryAttribute::Type type,
                                                     draco::DataType dataType, int components,
                                                     const std::string& what) {
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

}  // namespace

Expected<std::string> encodeDracoPayload(const RegionMesh& mesh, IdCoding coding,
                                         const RegionLattice* lattice, const QuantizationGrid& grid,
                                         int compressionLevel, const std::string& where) {
  TESSERA_ASSIGN_OR_RETURN(const std::unique_ptr<draco::Mesh> dracoMesh,
                           buildDracoMesh(mesh, coding, lattice));

  draco::Encoder encoder;
  TESSERA_RETURN_IF_ERROR(setExplicitQuantization(encoder, grid).withContext(where));
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, grid.normalBits);
  // Ids are labels, not geometry: a parallelogram of ids predicts nothing,
  // while the difference from the previous vertex in Draco's traversal
  // follows the locality of the numbering (smaller and faster on fandisk
  // regions; docs/REGION_ENCODING.md).
  // Lattice points are coordinates on the mesh: a parallelogram of them
  // predicts the next exactly wherever the tessellation is regular.
  const draco::Status idPrediction = encoder.SetAttributePredictionScheme(
      draco::GeometryAttribute::GENERIC,
      coding == IdCoding::kLattice ? draco::MESH_PREDICTION_PARALLELOGRAM : draco::PREDICTION_DIFFERENCE);
  if (!idPrediction.ok())
    return internalError(where + ": Draco refused the id prediction: " + idPrediction.error_msg_string());
  const int speed = kMaxCompressionLevel - compressionLevel;
  encoder.SetSpeedOptions(speed, speed);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*dracoMesh, &buffer);
  if (!status.ok()) return internalError(where + ": Draco encoding failed: " + status.error_msg_string());
  return std::string(buffer.data(), buffer.size());
}

// The counts are read from the header (DracoHeader in
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
    return parseError(r.source() + ": bitstream version " + std::to_string(major) + "." +
                      std::to_string(minor) + ", expected " +
                      std::to_string(draco::kDracoMeshBitstreamVersionMajor) + "." +
                      std::to_string(draco::kDracoMeshBitstreamVersionMinor));
  }
  TESSERA_RETURN_IF_ERROR(r.get(geometry, "the Draco geometry type"));
  TESSERA_RETURN_IF_ERROR(r.get(method, "the Draco method"));
  TESSERA_RETURN_IF_ERROR(r.get(flags, "the Draco flags"));
  if (geometry != draco::TRIANGULAR_MESH) return parseError(r.source() + ": not a triangle mesh");
  if (flags != 0)
    return parseError(r.source() + ": unexpected flags " + std::to_string(flags) + " (metadata?)");

  uint32_t faces = 0, vertices = 0;
  if (method == draco::MESH_SEQUENTIAL_ENCODING) {
    TESSERA_RETURN_IF_ERROR(getVarint(r, faces, "the face count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, vertices, "the point count"));
  } else if (method == draco::MESH_EDGEBREAKER_ENCODING) {
    uint8_t traversal = 0, attributeData = 0;
    uint32_t symbols = 0, splitSymbols = 0;
    TESSERA_RETURN_IF_ERROR(r.get(traversal, "the Edgebreaker traversal type"));
    if (traversal != draco::MESH_EDGEBREAKER_STANDARD_ENCODING &&
        traversal != draco::MESH_EDGEBREAKER_VALENCE_ENCODING) {
      return parseError(r.source() + ": unknown Edgebreaker traversal type " + std::to_string(traversal));
    }
    TESSERA_RETURN_IF_ERROR(getVarint(r, vertices, "the vertex count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, faces, "the face count"));
    TESSERA_RETURN_IF_ERROR(r.get(attributeData, "the attribute data count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, symbols, "the symbol count"));
    TESSERA_RETURN_IF_ERROR(getVarint(r, splitSymbols, "the split symbol count"));
    if (symbols > faces || splitSymbols > symbols || attributeData > 3) {
      return parseError(r.source() + ": inconsistent Edgebreaker counts (" + std::to_string(faces) +
                        " faces, " + std::to_string(symbols) + " symbols, " + std::to_string(splitSymbols) +
                        " splits)");
    }
  } else {
    return parseError(r.source() + ": unknown mesh method " + std::to_string(method));
  }
  if (faces != triangles) {
    return parseError(r.source() + ": " + std::to_string(faces) + " faces, the header announces " +
                      std::to_string(triangles));
  }
  if (vertices > 3 * static_cast<uint64_t>(faces)) {
    return parseError(r.source() + ": " + std::to_string(vertices) + " vertices for " +
                      std::to_string(faces) + " faces (at most 3 per face)");
  }
  return Status::ok();
}

Expected<RegionMesh> decodeDracoPayload(std::string_view payload, const QuantizationGrid& grid, bool withIds,
                                        uint32_t triangles, const RegionLattice* lattice,
                                        const std::string& where) {
  draco::DecoderBuffer buffer;
  buffer.Init(payload.data(), payload.size());
  draco::Decoder decoder;
  // Positions come back as lattice indices with their quantization
  // parameters, which are checked against the header and range-checked below.
  decoder.SetSkipAttributeTransform(draco::GeometryAttribute::POSITION);
  auto decodedOr = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decodedOr.ok())
    return parseError(where + ": Draco rejected the payload: " + decodedOr.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decodedOr).value();
  const uint32_t points = mesh->num_points();
  const int attributes = withIds ? 3 : 2;
  if (mesh->num_faces() != triangles || points > 3 * static_cast<uint64_t>(triangles) ||
      mesh->num_attributes() != attributes) {
    return parseError(where + ": Draco decoded " + std::to_string(mesh->num_faces()) + " faces, " +
                      std::to_string(points) + " points and " + std::to_string(mesh->num_attributes()) +
                      " attributes; expected " + std::to_string(triangles) + " faces, " +
                      std::to_string(attributes) + " attributes");
  }
  TESSERA_ASSIGN_OR_RETURN(
      const draco::PointAttribute* positions,
      findAttribute(*mesh, draco::GeometryAttribute::POSITION, draco::DT_INT32, 3, where + ": POSITION"));
  TESSERA_ASSIGN_OR_RETURN(
      const draco::PointAttribute* normals,
      findAttribute(*mesh, draco::GeometryAttribute::NORMAL, draco::DT_FLOAT32, 3, where + ": NORMAL"));
  const draco::PointAttribute* ids = nullptr;
  if (withIds) {
    TESSERA_ASSIGN_OR_RETURN(
        ids, findAttribute(*mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT8,
                           lattice ? kLatticeComponents : kIdComponents, where + ": vertex ids"));
  }

  draco::AttributeQuantizationTransform quantization;
  if (!quantization.InitFromAttribute(*positions) || quantization.quantization_bits() != grid.positionBits ||
      quantization.range() != static_cast<float>(grid.range) ||
      quantization.min_value(0) != static_cast<float>(grid.origin[0]) ||
      quantization.min_value(1) != static_cast<float>(grid.origin[1]) ||
      quantization.min_value(2) != static_cast<float>(grid.origin[2])) {
    return parseError(where + ": Draco's position quantization differs from the header's grid");
  }
  const int32_t maxIndex = static_cast<int32_t>((uint32_t{1} << grid.positionBits) - 1);
  draco::Dequantizer dequantizer;
  if (!dequantizer.Init(quantization.range(), maxIndex))
    return parseError(where + ": unusable quantization range");

  RegionMesh out;
  out.positions.resize(points);
  out.normals.resize(points);
  if (withIds) out.vertexIds.resize(points);
  for (draco::PointIndex p(0); p < points; ++p) {
    const auto point = [&p] { return "point " + std::to_string(p.value()); };
    const draco::AttributeValueIndex pi = positions->mapped_index(p), ni = normals->mapped_index(p),
                                     ii = withIds ? ids->mapped_index(p) : draco::AttributeValueIndex(0);
    if (pi.value() >= positions->size() || ni.value() >= normals->size() ||
        (withIds && ii.value() >= ids->size())) {
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
    if (!isFinite(normal) || !(normal.norm() > 0.5))
      return parseError(where + ": " + point() + " has no unit normal");
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
        return parseError(where + ": face " + std::to_string(f.value()) + " uses a point beyond " +
                          std::to_string(points));
      }
      out.triangles[f.value()][c] = static_cast<int>(face[c].value());
    }
  }
  return out;
}

}  // namespace tessera::region_detail
