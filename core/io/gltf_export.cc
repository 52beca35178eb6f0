#include "core/io/gltf_export.h"

#include <tiny_gltf.h>  // the shared libtinygltf carries the implementation

#include <algorithm>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "core/io/draco_encode.h"
#include "core/io/export_common.h"
#include "core/io/mesh_writers.h"

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
  if (!options.draco) {
    // The plain form is streamed (mesh_writers.h): tinygltf would hold the
    // buffer three times over.
    TESSERA_ASSIGN_OR_RETURN(FileWriter out, FileWriter::open(path));
    writePlainGlb(surface, out);
    return out.close();
  }
  tinygltf::Model model = makeModelSkeleton();
  TESSERA_ASSIGN_OR_RETURN(tinygltf::Primitive primitive, fillDraco(model, surface, options));
  model.meshes[0].primitives.push_back(std::move(primitive));
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
