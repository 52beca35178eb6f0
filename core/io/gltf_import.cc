// glTF/GLB import through tinygltf (the shared library build; this file must
// not define TINYGLTF_IMPLEMENTATION). See gltf_import.h for the choices made.
#include "core/io/gltf_import.h"

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <tuple>

#include <tiny_gltf.h>

#include "core/io/glb_container.h"
#include "core/io/gltf_draco.h"

namespace tessera {
namespace {

// Images are irrelevant to geometry; skipping them also keeps a corrupt image
// from failing (or slowing) the mesh import.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
  return true;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// Filesystem callbacks that read nothing: an import from bytes must not
// touch the filesystem, so a .gltf naming external buffers fails, naming them.
tinygltf::FsCallbacks noFiles() {
  tinygltf::FsCallbacks callbacks{};
  callbacks.FileExists = [](const std::string&, void*) { return false; };
  callbacks.ExpandFilePath = [](const std::string& path, void*) { return path; };
  callbacks.ReadWholeFile = [](std::vector<unsigned char>*, std::string* err, const std::string& path,
                               void*) {
    if (err) *err += "external file '" + path + "' cannot be read here: send a .glb (or data: URIs)\n";
    return false;
  };
  callbacks.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&,
                                void*) {
    if (err) *err += "writing is not supported\n";
    return false;
  };
  return callbacks;
}

// Bounds-checked view of an accessor's elements.
struct AccessorView {
  const unsigned char* data = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int componentType = 0;
};

Status viewAccessor(const tinygltf::Model& model, int index, int expectedType, const std::string& where,
                    AccessorView& view) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size())) {
    return parseError(where + ": accessor " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Accessor& acc = model.accessors[index];
  const std::string name = where + ": accessor " + std::to_string(index);
  if (acc.sparse.isSparse) return unsupported(name + ": sparse accessors are not supported");
  if (acc.type != expectedType)
    return parseError(name + ": unexpected element type " + std::to_string(acc.type));
  if (acc.bufferView < 0 || acc.bufferView >= static_cast<int>(model.bufferViews.size())) {
    return parseError(name + ": has no valid bufferView");
  }
  const tinygltf::BufferView& bv = model.bufferViews[acc.bufferView];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size())) {
    return parseError(name + ": bufferView " + std::to_string(acc.bufferView) + " names no valid buffer");
  }
  const std::vector<unsigned char>& buffer = model.buffers[bv.buffer].data;
  const int stride = acc.ByteStride(bv);
  const int elementSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType)) *
                          tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
  if (stride <= 0 || elementSize <= 0) return parseError(name + ": invalid component type or stride");
  const uint64_t viewEnd = static_cast<uint64_t>(bv.byteOffset) + bv.byteLength;
  const uint64_t needed = acc.count == 0 ? 0
                                         : static_cast<uint64_t>(acc.byteOffset) +
                                               static_cast<uint64_t>(stride) * (acc.count - 1) + elementSize;
  if (viewEnd > buffer.size() || needed > bv.byteLength) {
    return parseError(name + ": data runs past the end of its buffer (truncated file?)");
  }
  view.data = buffer.data() + bv.byteOffset + acc.byteOffset;
  view.count = acc.count;
  view.stride = static_cast<size_t>(stride);
  view.componentType = acc.componentType;
  return Status::ok();
}

Status readIndex(const AccessorView& view, size_t i, uint32_t& out) {
  const unsigned char* p = view.data + i * view.stride;
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      out = *p;
      return Status::ok();
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      out = v;
      return Status::ok();
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      out = v;
      return Status::ok();
    }
    default:
      return parseError("index component type " + std::to_string(view.componentType) + " is not allowed");
  }
}

// Mesh-level vertex bookkeeping: original (per-mesh, pre-weld) number ->
// soup index.
struct MeshVertices {
  std::vector<int> soupIndex;
};

// Without converting: a double outside int64's range (a JSON index of 37
// digits) makes that conversion undefined (UBSan, found by fuzz_import_gltf).
bool isIntegral(const tinygltf::Value& v) {
  if (v.IsInt()) return true;
  if (!v.IsReal()) return false;
  const double d = v.GetNumberAsDouble();
  return std::isfinite(d) && d == std::trunc(d);
}

Status parseExtrasTags(const tinygltf::Value& extras, const std::string& meshName,
                       const MeshVertices& vertices, GltfContent& content, std::vector<std::string>& names) {
  if (!extras.IsObject() || !extras.Has("tessera")) return Status::ok();
  const tinygltf::Value& tessera = extras.Get("tessera");
  const std::string base = meshName + ".extras.tessera";
  if (!tessera.IsObject()) return parseError(base + ": expected an object with 'creases' and/or 'corners'");
  for (const std::string& key : tessera.Keys()) {
    if (key != "creases" && key != "corners") {
      return parseError(base + ": unknown key '" + key + "' (expected 'creases' or 'corners')");
    }
  }
  for (const char* key : {"creases", "corners"}) {
    if (!tessera.Has(key)) continue;
    const tinygltf::Value& list = tessera.Get(key);
    const bool crease = std::strcmp(key, "creases") == 0;
    if (!list.IsArray()) return parseError(base + "." + key + ": expected an array");
    const size_t arity = crease ? 3 : 2;
    for (size_t i = 0; i < list.ArrayLen(); ++i) {
      const std::string name = base + "." + key + "[" + std::to_string(i) + "]";
      const tinygltf::Value& item = list.Get(static_cast<int>(i));
      const std::string usage = crease ? "[i, j, sharpness]" : "[i, sharpness]";
      if (!item.IsArray() || item.ArrayLen() != arity) return parseError(name + ": expected " + usage);
      FeatureTag tag;
      tag.kind = crease ? FeatureTag::Kind::kCrease : FeatureTag::Kind::kCorner;
      int mapped[2] = {-1, -1};
      for (size_t k = 0; k + 1 < arity; ++k) {
        const tinygltf::Value& v = item.Get(static_cast<int>(k));
        const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
        if (!isIntegral(v) || d < 0 || d >= static_cast<double>(vertices.soupIndex.size())) {
          return notFound(name + ": vertex index must be an integer in [0, " +
                          std::to_string(vertices.soupIndex.size()) + ")");
        }
        mapped[k] = vertices.soupIndex[static_cast<size_t>(d)];
      }
      const tinygltf::Value& s = item.Get(static_cast<int>(arity - 1));
      bool ok = false;
      if (s.IsString()) {
        ok = parseSharpness(s.Get<std::string>(), tag.sharpness);
      } else if (s.IsNumber()) {
        ok = parseSharpness(std::to_string(s.GetNumberAsDouble()), tag.sharpness);
      }
      if (!ok) return invalidArgument(name + ": sharpness must be a number >= 0 or the string \"inf\"");
      tag.v0 = mapped[0];
      tag.v1 = crease ? mapped[1] : -1;
      if (crease && tag.v0 == tag.v1) {
        return invalidArgument(name + ": both ends are the same vertex (after welding equal positions)");
      }
      tag.line = static_cast<int>(names.size());
      names.push_back(name);
      content.tags.push_back(tag);
    }
  }
  return Status::ok();
}

// A primitive's positions and triangle corners, from accessors or decoded
// from KHR_draco_mesh_compression.
struct PrimitiveData {
  std::vector<std::array<float, 3>> positions;
  std::vector<uint32_t> indices;
};

Status readAccessors(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                     PrimitiveData& out) {
  auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) return parseError(where + ": has no POSITION attribute");
  AccessorView positions;
  TESSERA_RETURN_IF_ERROR(viewAccessor(model, pos->second, TINYGLTF_TYPE_VEC3, where, positions));
  if (positions.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    return unsupported(where + ": POSITION must be FLOAT (quantized positions are not supported)");
  }
  out.positions.resize(positions.count);
  for (size_t i = 0; i < positions.count; ++i) {
    std::memcpy(out.positions[i].data(), positions.data + i * positions.stride, 3 * sizeof(float));
  }
  if (prim.indices >= 0) {
    AccessorView view;
    TESSERA_RETURN_IF_ERROR(viewAccessor(model, prim.indices, TINYGLTF_TYPE_SCALAR, where, view));
    out.indices.resize(view.count);
    for (size_t i = 0; i < view.count; ++i) {
      Status status = readIndex(view, i, out.indices[i]);
      if (!status.isOk()) return status.withContext(where + ": accessor " + std::to_string(prim.indices));
    }
  } else {
    out.indices.resize(positions.count);
    for (size_t i = 0; i < out.indices.size(); ++i) out.indices[i] = static_cast<uint32_t>(i);
  }
  return Status::ok();
}

Status readDraco(const tinygltf::Model& model, const tinygltf::Value& extension, const std::string& where,
                 PrimitiveData& out) {
  const std::string name = where + ": " + io_detail::kDracoExtension;
  if (!extension.IsObject() || !extension.Has("bufferView") || !extension.Get("bufferView").IsNumber() ||
      !extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
    return parseError(name + ": needs a bufferView and attributes");
  }
  const tinygltf::Value& attributes = extension.Get("attributes");
  if (!attributes.Has("POSITION") || !attributes.Get("POSITION").IsNumber()) {
    return parseError(name + ": attributes has no POSITION id");
  }
  const int viewIndex = extension.Get("bufferView").GetNumberAsInt();
  if (viewIndex < 0 || viewIndex >= static_cast<int>(model.bufferViews.size())) {
    return parseError(name + ": bufferView " + std::to_string(viewIndex) + " does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()) ||
      static_cast<uint64_t>(view.byteOffset) + view.byteLength > model.buffers[view.buffer].data.size()) {
    return parseError(name + ": bufferView " + std::to_string(viewIndex) +
                      " runs past its buffer (truncated file?)");
  }
  TESSERA_ASSIGN_OR_RETURN(
      io_detail::DracoPrimitive decoded,
      io_detail::decodeDracoPrimitive(model.buffers[view.buffer].data.data() + view.byteOffset,
                                      view.byteLength, attributes.Get("POSITION").GetNumberAsInt(), name));
  out.positions = std::move(decoded.positions);
  out.indices = std::move(decoded.indices);
  return Status::ok();
}

Status readPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                     MeshVertices& vertices, std::map<std::tuple<float, float, float>, int>& weld,
                     PolygonSoup& soup) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES) {
    return unsupported(where + ": mode " + std::to_string(mode) + " is not supported, only TRIANGLES (4)");
  }
  PrimitiveData data;
  auto draco = prim.extensions.find(io_detail::kDracoExtension);
  if (draco != prim.extensions.end()) {
    TESSERA_RETURN_IF_ERROR(readDraco(model, draco->second, where, data));
  } else {
    TESSERA_RETURN_IF_ERROR(readAccessors(model, prim, where, data));
  }
  const size_t first = vertices.soupIndex.size();
  for (const auto& xyz : data.positions) {
    // Exact float equality (so -0 == +0); NaN never equals itself, so a NaN
    // vertex stays separate and validation names it.
    const auto key = std::make_tuple(xyz[0] + 0.0f, xyz[1] + 0.0f, xyz[2] + 0.0f);
    const bool weldable = xyz[0] == xyz[0] && xyz[1] == xyz[1] && xyz[2] == xyz[2];
    auto it = weldable ? weld.find(key) : weld.end();
    if (it != weld.end()) {
      vertices.soupIndex.push_back(it->second);
      continue;
    }
    const int index = static_cast<int>(soup.points.size());
    soup.points.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (weldable) weld.emplace(key, index);
    vertices.soupIndex.push_back(index);
  }
  if (data.indices.size() % 3 != 0) {
    return parseError(where + ": " + std::to_string(data.indices.size()) + " indices, not a multiple of 3");
  }
  for (size_t t = 0; t < data.indices.size(); t += 3) {
    std::vector<int> face(3);
    for (int k = 0; k < 3; ++k) {
      const uint32_t local = data.indices[t + k];
      if (local >= data.positions.size()) {
        return invalidMesh(where + ": triangle " + std::to_string(t / 3) + ": vertex index " +
                           std::to_string(local) + " is out of range (the primitive has " +
                           std::to_string(data.positions.size()) + " vertices)");
      }
      face[k] = vertices.soupIndex[first + local];
    }
    soup.addFace(face);
  }
  return Status::ok();
}

}  // namespace

Expected<GltfContent> readGltf(const std::string& path, const std::string& original,
                               const std::string* baseDir) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  if (baseDir == nullptr) loader.SetFsCallbacks(noFiles());
  tinygltf::Model model;
  std::string err, warn;
  if (original.size() >= 4 && original.compare(0, 4, "glTF") == 0)
    TESSERA_RETURN_IF_ERROR(io_detail::checkGlbContainer(original, path));
  TESSERA_ASSIGN_OR_RETURN(const std::string data, io_detail::dropDracoIndices(original, path));
  const std::string dir = baseDir == nullptr ? std::string() : *baseDir;
  const bool binary = data.size() >= 4 && data.compare(0, 4, "glTF") == 0;
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                              reinterpret_cast<const unsigned char*>(data.data()),
                                              static_cast<unsigned int>(data.size()), dir)
                : loader.LoadASCIIFromString(&model, &err, &warn, data.data(),
                                             static_cast<unsigned int>(data.size()), dir);
  } catch (const std::exception& e) {
    return parseError(path + ": malformed glTF: " + e.what());
  }
  if (!ok)
    return parseError(path +
                      ": malformed glTF: " + (err.empty() ? "tinygltf could not load it" : trimmed(err)));
  if (model.meshes.empty()) return invalidMesh(path + ": mesh: empty, the file has no meshes");

  GltfContent content;
  auto names = std::make_shared<std::vector<std::string>>();
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const std::string meshName = "meshes[" + std::to_string(m) + "]";
    MeshVertices vertices;
    std::map<std::tuple<float, float, float>, int> weld;  // per mesh: meshes are never welded together
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const std::string where = path + ": " + meshName + ".primitives[" + std::to_string(p) + "]";
      TESSERA_RETURN_IF_ERROR(
          readPrimitive(model, model.meshes[m].primitives[p], where, vertices, weld, content.soup));
    }
    TESSERA_RETURN_IF_ERROR(
        parseExtrasTags(model.meshes[m].extras, path + ": " + meshName, vertices, content, *names));
  }
  content.locate = [names](const FeatureTag& tag) { return (*names)[static_cast<size_t>(tag.line)]; };
  return content;
}

}  // namespace tessera
