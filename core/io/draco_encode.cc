#include "core/io/draco_encode.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <string>

#include "core/io/export_common.h"

namespace tessera::io_detail {
namespace {

// Draco's limits (draco/compression/draco_compression_options.h and the
// octahedral normal transform): positions take 1..30 bits; normals need at
// least 2 bits because the octahedral square needs a centre.
constexpr int kMinPositionBits = 1;
constexpr int kMinNormalBits = 2;
constexpr int kMaxQuantizationBits = 30;
constexpr int kMaxCompressionLevel = 10;

// A float32 3-component attribute with one value per point (identity mapping),
// which is what a SurfaceMesh is: positions and normals share one index.
int addFloat3Attribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, std::size_t count) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  return mesh.AddAttribute(attribute, /*identity_mapping=*/true, static_cast<std::uint32_t>(count));
}

// draco::Mesh is neither copyable nor movable, hence the unique_ptr.
std::unique_ptr<draco::Mesh> buildDracoMesh(const SurfaceMesh& surface, int& positionId, int& normalId) {
  auto meshPtr = std::make_unique<draco::Mesh>();
  draco::Mesh& mesh = *meshPtr;
  mesh.set_num_points(static_cast<std::uint32_t>(surface.positions.size()));
  mesh.SetNumFaces(surface.triangles.size());
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c)
      face[c] = draco::PointIndex(static_cast<std::uint32_t>(surface.triangles[f][c]));
    mesh.SetFace(draco::FaceIndex(static_cast<std::uint32_t>(f)), face);
  }

  positionId = addFloat3Attribute(mesh, draco::GeometryAttribute::POSITION, surface.positions.size());
  draco::PointAttribute* positions = mesh.attribute(positionId);
  for (std::size_t i = 0; i < surface.positions.size(); ++i) {
    const std::array<float, 3> value = toFloat3(surface.positions[i]);
    positions->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)), value.data());
  }

  normalId = -1;
  if (!surface.normals.empty()) {
    normalId = addFloat3Attribute(mesh, draco::GeometryAttribute::NORMAL, surface.normals.size());
    draco::PointAttribute* normals = mesh.attribute(normalId);
    for (std::size_t i = 0; i < surface.normals.size(); ++i) {
      const std::array<float, 3> value = unitFloat3(surface.normals[i]);
      normals->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(i)), value.data());
    }
  }
  return meshPtr;
}

// Decodes what we just encoded and records the counts and position bounds the
// glTF accessors must state (KHR_draco_mesh_compression, "accessors": they
// "must match the decompressed data").
Status measureDecoded(DracoEncodedMesh& encoded) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(encoded.bytes.data()), encoded.bytes.size());
  draco::Decoder decoder;
  auto decodedOr = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decodedOr.ok()) {
    return internalError("Draco could not decode its own output: " + decodedOr.status().error_msg_string());
  }
  const std::unique_ptr<draco::Mesh> decoded = std::move(decodedOr).value();
  const draco::PointAttribute* positions =
      decoded->GetAttributeByUniqueId(static_cast<std::uint32_t>(encoded.positionUniqueId));
  if (positions == nullptr) return internalError("decoded Draco mesh has no POSITION attribute");
  if (encoded.normalUniqueId >= 0 &&
      decoded->GetAttributeByUniqueId(static_cast<std::uint32_t>(encoded.normalUniqueId)) == nullptr) {
    return internalError("decoded Draco mesh has no NORMAL attribute");
  }

  encoded.pointCount = decoded->num_points();
  encoded.faceCount = decoded->num_faces();
  if (encoded.pointCount == 0 || encoded.faceCount == 0) return internalError("decoded Draco mesh is empty");
  encoded.positionMin.fill(std::numeric_limits<float>::max());
  encoded.positionMax.fill(std::numeric_limits<float>::lowest());
  for (draco::PointIndex p(0); p < decoded->num_points(); ++p) {
    std::array<float, 3> value{};
    if (!positions->ConvertValue<float, 3>(positions->mapped_index(p), value.data())) {
      return internalError("decoded Draco position " + std::to_string(p.value()) +
                           " is not convertible to float");
    }
    for (int k = 0; k < 3; ++k) {
      encoded.positionMin[k] = std::min(encoded.positionMin[k], value[k]);
      encoded.positionMax[k] = std::max(encoded.positionMax[k], value[k]);
    }
  }
  return Status::ok();
}

}  // namespace

Status validateDracoOptions(const ExportOptions& options) {
  if (options.dracoPositionBits < kMinPositionBits || options.dracoPositionBits > kMaxQuantizationBits) {
    return invalidArgument("dracoPositionBits " + std::to_string(options.dracoPositionBits) + " outside [" +
                           std::to_string(kMinPositionBits) + ", " + std::to_string(kMaxQuantizationBits) +
                           "]");
  }
  if (options.dracoNormalBits < kMinNormalBits || options.dracoNormalBits > kMaxQuantizationBits) {
    return invalidArgument("dracoNormalBits " + std::to_string(options.dracoNormalBits) + " outside [" +
                           std::to_string(kMinNormalBits) + ", " + std::to_string(kMaxQuantizationBits) +
                           "]");
  }
  if (options.dracoCompressionLevel < 0 || options.dracoCompressionLevel > kMaxCompressionLevel) {
    return invalidArgument("dracoCompressionLevel " + std::to_string(options.dracoCompressionLevel) +
                           " outside [0, " + std::to_string(kMaxCompressionLevel) + "]");
  }
  return Status::ok();
}

Expected<DracoEncodedMesh> encodeDraco(const SurfaceMesh& surface, const ExportOptions& options) {
  TESSERA_RETURN_IF_ERROR(validateDracoOptions(options));
  int positionId = -1;
  int normalId = -1;
  const std::unique_ptr<draco::Mesh> meshPtr = buildDracoMesh(surface, positionId, normalId);
  const draco::Mesh& mesh = *meshPtr;
  if (positionId < 0 || (!surface.normals.empty() && normalId < 0)) {
    return internalError("Draco refused to add an attribute");
  }

  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.dracoPositionBits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, options.dracoNormalBits);
  // Draco's speed runs the other way from our level: 0 is its smallest output
  // (edgebreaker, strongest prediction), 10 its fastest (sequential coding).
  const int speed = kMaxCompressionLevel - options.dracoCompressionLevel;
  encoder.SetSpeedOptions(speed, speed);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok()) return internalError("Draco encoding failed: " + status.error_msg_string());

  DracoEncodedMesh encoded;
  encoded.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  encoded.positionUniqueId = static_cast<int>(mesh.attribute(positionId)->unique_id());
  if (normalId >= 0) encoded.normalUniqueId = static_cast<int>(mesh.attribute(normalId)->unique_id());
  TESSERA_RETURN_IF_ERROR(measureDecoded(encoded));
  return encoded;
}

}  // namespace tessera::io_detail
