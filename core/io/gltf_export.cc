#include "core/io/gltf_export.h"

#include <tiny_gltf.h>  // the shared libtinygltf carries the implementation

#include <algorithm>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "core/io/draco_encode.h"
#include "core/io/export_common.h"

namespace tessera::io_detail {
namespace {

constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";

// glTF 2.0, 3.7.2.1: an indices accessor must not contain the largest value of
// its component type (primitive restart in some APIs), so 16-bit indices are
// usable only while every index is at most 65534.
constexpr std::size_t kMaxUnsignedShortVertices = std::numeric_limits<std::uint16_t>::max();

int indexComponentType(std::size_t vertexCount) {
  return vertexCount <= kMaxUnsignedShortVertices ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                                  : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// Appends `size` bytes to buffer 0 as a new bufferView and returns its index.
// Every view starts on a 4-byte boundary: glTF 2.0, 3.6.2.4 requires accessor
// offsets to be multiples of the component size (4 for FLOAT and
// UNSIGNED_INT), and the GLB BIN chunk itself is 4-byte aligned.
// target 0 means "none": the Draco view is not vertex or index data.
int appendBufferView(tinygltf::Model& model, const void* data, std::size_t size, int target) {
  std::vector<unsigned char>& bytes = model.buffers[0].data;
  bytes.resize((bytes.size() + 3) & ~std::size_t{3}, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bytes.size();
  view.byteLength = size;
  view.target = target;
  const auto* first = static_cast<const unsigned char*>(data);
  bytes.insert(bytes.end(), first, first + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

// bufferView -1 leaves the accessor without data, as KHR_draco_mesh_compression
// requires for attributes that exist only in compressed form.
int addAccessor(tinygltf::Model& model, int bufferView, int componentType, int type, std::size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = bufferView;
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

// POSITION accessors must carry min and max (glTF 2.0, 3.7.2.1). They must be
// the bounds of the float32 data actually stored, hence floats in, not doubles.
void setBounds(tinygltf::Model& model, int accessor, const std::array<float, 3>& lo,
               const std::array<float, 3>& hi) {
  model.accessors[accessor].minValues.assign(lo.begin(), lo.end());
  model.accessors[accessor].maxValues.assign(hi.begin(), hi.end());
}

template <typename Index>
int appendIndices(tinygltf::Model& model, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<Index> indices;
  indices.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    for (int v : t) indices.push_back(static_cast<Index>(v));
  }
  return appendBufferView(model, indices.data(), indices.size() * sizeof(Index),
                          TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

tinygltf::Model makeModelSkeleton() {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Tessera";
  model.buffers.resize(1);  // no uri: written as the GLB BIN chunk
  model.meshes.resize(1);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

tinygltf::Primitive fillPlain(tinygltf::Model& model, const SurfaceMesh& surface) {
  const std::size_t n = surface.positions.size();
  std::vector<std::array<float, 3>> positions(n);
  std::array<float, 3> lo;
  std::array<float, 3> hi;
  lo.fill(std::numeric_limits<float>::max());
  hi.fill(std::numeric_limits<float>::lowest());
  for (std::size_t i = 0; i < n; ++i) {
    positions[i] = toFloat3(surface.positions[i]);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], positions[i][k]);
      hi[k] = std::max(hi[k], positions[i][k]);
    }
  }

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  const int positionView =
      appendBufferView(model, positions.data(), n * sizeof(positions[0]), TINYGLTF_TARGET_ARRAY_BUFFER);
  const int positionAccessor =
      addAccessor(model, positionView, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  setBounds(model, positionAccessor, lo, hi);
  primitive.attributes["POSITION"] = positionAccessor;

  if (!surface.normals.empty()) {
    std::vector<std::array<float, 3>> normals(n);
    for (std::size_t i = 0; i < n; ++i) normals[i] = unitFloat3(surface.normals[i]);
    const int normalView =
        appendBufferView(model, normals.data(), n * sizeof(normals[0]), TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.attributes["NORMAL"] =
        addAccessor(model, normalView, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  }

  const int indexType = indexComponentType(n);
  const int indexView = indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                            ? appendIndices<std::uint16_t>(model, surface.triangles)
                            : appendIndices<std::uint32_t>(model, surface.triangles);
  primitive.indices = addAccessor(model, indexView, indexType, TINYGLTF_TYPE_SCALAR, surface.triangles.size() * 3);
  return primitive;
}

// KHR_draco_mesh_compression: the primitive keeps its attributes and indices
// accessors (count, type, bounds of the decoded data) but without bufferView;
// the extension object names the compressed bufferView and maps each glTF
// attribute to the Draco attribute unique id. No uncompressed fallback is
// written, so the extension is required as well as used.
Expected<tinygltf::Primitive> fillDraco(tinygltf::Model& model, const SurfaceMesh& surface,
                                        const ExportOptions& options) {
  TESSERA_ASSIGN_OR_RETURN(const DracoEncodedMesh encoded, encodeDraco(surface, options));

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  const int dracoView = appendBufferView(model, encoded.bytes.data(), encoded.bytes.size(), 0);

  const int positionAccessor =
      addAccessor(model, -1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, encoded.pointCount);
  setBounds(model, positionAccessor, encoded.positionMin, encoded.positionMax);
  primitive.attributes["POSITION"] = positionAccessor;
  tinygltf::Value::Object dracoAttributes;
  dracoAttributes["POSITION"] = tinygltf::Value(encoded.positionUniqueId);
  if (encoded.normalUniqueId >= 0) {
    primitive.attributes["NORMAL"] =
        addAccessor(model, -1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, encoded.pointCount);
    dracoAttributes["NORMAL"] = tinygltf::Value(encoded.normalUniqueId);
  }
  primitive.indices = addAccessor(model, -1, indexComponentType(encoded.pointCount), TINYGLTF_TYPE_SCALAR,
                                  encoded.faceCount * 3);

  tinygltf::Value::Object extension;
  extension["bufferView"] = tinygltf::Value(dracoView);
  extension["attributes"] = tinygltf::Value(std::move(dracoAttributes));
  primitive.extensions[kDracoExtension] = tinygltf::Value(std::move(extension));
  model.extensionsUsed.push_back(kDracoExtension);
  model.extensionsRequired.push_back(kDracoExtension);
  return primitive;
}

}  // namespace

Status writeGlb(const SurfaceMesh& surface, const std::string& path, const ExportOptions& options) {
  tinygltf::Model model = makeModelSkeleton();
  if (options.draco) {
    TESSERA_ASSIGN_OR_RETURN(tinygltf::Primitive primitive, fillDraco(model, surface, options));
    model.meshes[0].primitives.push_back(std::move(primitive));
  } else {
    model.meshes[0].primitives.push_back(fillPlain(model, surface));
  }
  // The buffer's byteLength should match the BIN chunk, which GLB pads to 4.
  std::vector<unsigned char>& bytes = model.buffers[0].data;
  bytes.resize((bytes.size() + 3) & ~std::size_t{3}, 0);

  // Serialise to memory and write the file ourselves: tinygltf 2.7's
  // WriteGltfSceneToFile neither checks that the file opened nor that the
  // writes succeeded, so it reports success for an unwritable path. The
  // stream variant produces the same GLB (buffer 0 without uri becomes the
  // BIN chunk; prettyPrint is irrelevant for binary output).
  std::ostringstream glb(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, glb, /*prettyPrint=*/false, /*writeBinary=*/true)) {
    return internalError("tinygltf could not serialise the GLB");
  }
  const std::string data = std::move(glb).str();
  return writeFileBytes(path, data.data(), data.size());
}

}  // namespace tessera::io_detail
