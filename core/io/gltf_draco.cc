#include "core/io/gltf_draco.h"

#include <cstring>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <nlohmann/json.hpp>

#include "core/io/glb_container.h"

namespace tessera::io_detail {

namespace {

void appendU32(std::string& out, uint32_t value) {
  out.append(reinterpret_cast<const char*>(&value), 4);
}

// Removes "indices" from each compressed primitive; false if none is.
bool dropIndices(nlohmann::json& gltf) {
  bool changed = false;
  if (!gltf.is_object() || !gltf.contains("meshes") || !gltf["meshes"].is_array()) return false;
  for (auto& mesh : gltf["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (auto& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("extensions")) continue;
      const auto& extensions = primitive["extensions"];
      if (!extensions.is_object() || !extensions.contains(kDracoExtension)) continue;
      changed = primitive.erase("indices") > 0 || changed;
    }
  }
  return changed;
}

}  // namespace

Expected<std::string> dropDracoIndices(const std::string& data, const std::string& name) {
  // Cheap test first: most files never name the extension.
  if (data.find(kDracoExtension) == std::string::npos) return data;
  const bool binary = data.size() >= 4 && glbU32At(data, 0) == kGlbMagic;
  std::string json;
  size_t rest = 0;  // where the GLB's chunks after the JSON start
  if (binary) {
    if (data.size() < kGlbHeaderBytes + kGlbChunkHeaderBytes ||
        glbU32At(data, kGlbHeaderBytes + 4) != kGlbJsonChunk) {
      return parseError(name + ": malformed GLB: no JSON chunk after the header");
    }
    const uint64_t jsonBytes = glbU32At(data, kGlbHeaderBytes);
    rest = kGlbHeaderBytes + kGlbChunkHeaderBytes + jsonBytes;
    if (rest > data.size())
      return parseError(name + ": malformed GLB: the JSON chunk runs past the end of the file");
    json = data.substr(kGlbHeaderBytes + kGlbChunkHeaderBytes, jsonBytes);
  } else {
    json = data;
  }
  nlohmann::json gltf = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (gltf.is_discarded()) return parseError(name + ": malformed glTF: the JSON does not parse");
  if (!dropIndices(gltf)) return data;
  std::string text = gltf.dump();
  if (!binary) return text;
  while (text.size() % 4 != 0) text.push_back(' ');  // chunks are 4-byte aligned, JSON padded with spaces
  std::string out;
  out.reserve(kGlbHeaderBytes + kGlbChunkHeaderBytes + text.size() + (data.size() - rest));
  appendU32(out, kGlbMagic);
  appendU32(out, glbU32At(data, 4));  // version
  appendU32(out, static_cast<uint32_t>(kGlbHeaderBytes + kGlbChunkHeaderBytes + text.size() +
                                       (data.size() - rest)));
  appendU32(out, static_cast<uint32_t>(text.size()));
  appendU32(out, kGlbJsonChunk);
  out += text;
  out.append(data, rest, std::string::npos);
  return out;
}

Expected<DracoPrimitive> decodeDracoPrimitive(const unsigned char* data, size_t size, int positionId,
                                              const std::string& where) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) return parseError(where + ": Draco data: " + type.status().error_msg_string());
  if (type.value() != draco::TRIANGULAR_MESH)
    return parseError(where + ": Draco data is not a triangle mesh");
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    return parseError(where + ": Draco data does not decode: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const draco::PointAttribute* position = mesh->GetAttributeByUniqueId(static_cast<uint32_t>(positionId));
  if (position == nullptr) {
    return parseError(where + ": the Draco data has no attribute " + std::to_string(positionId) +
                      " (the extension's POSITION)");
  }
  if (position->attribute_type() != draco::GeometryAttribute::POSITION || position->num_components() != 3) {
    return parseError(where + ": Draco attribute " + std::to_string(positionId) +
                      " is not a 3-component POSITION");
  }
  DracoPrimitive out;
  out.positions.resize(mesh->num_points());
  for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
    if (!position->ConvertValue<float, 3>(position->mapped_index(p), out.positions[p.value()].data())) {
      return parseError(where + ": Draco POSITION of point " + std::to_string(p.value()) +
                        " does not convert");
    }
  }
  out.indices.reserve(3 * static_cast<size_t>(mesh->num_faces()));
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) out.indices.push_back(mesh->face(f)[k].value());
  }
  return out;
}

}  // namespace tessera::io_detail
