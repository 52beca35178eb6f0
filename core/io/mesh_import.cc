// Mesh import through OpenMesh IO (OBJ, OFF, PLY, STL) and tinygltf (glTF).
//
// OpenMesh's readers are lenient in ways that would hide bad input: the OBJ
// reader drops vertices it cannot parse (renumbering every later vertex),
// removes repeated indices from a face and drops faces left with fewer than
// three corners; the OFF reader knows no comments and reads garbage counts and
// indices from a truncated file; the STL reader drops zero-length-edge facets.
// So each format is pre-scanned strictly first (format_prescan.h), with lines,
// and OpenMesh then reads into a PolygonSoup (never a TriMesh: its builder
// duplicates vertices of non-manifold faces silently). Counts are compared
// afterwards so that anything a reader still drops is an error, not a
// different mesh. buildBaseMesh() does the topological validation.
#include "core/io/mesh_import.h"

#include "core/util/file_io.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "core/io/format_prescan.h"
#include "core/io/gltf_import.h"
#include "core/io/soup_importer.h"
#include "core/io/tag_file.h"
#include "core/mesh/mesh_validation.h"

namespace tessera {
namespace {

// Silences OpenMesh's omerr/omout/omlog and std::cerr (some readers print to
// it directly) for the duration of a read, so CLI output stays ours.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : cerrBuffer_(std::cerr.rdbuf(captured_.rdbuf())) {
    for (auto* s : {&::omerr(), &::omout(), &::omlog()}) {
      wasEnabled_.push_back(s->is_enabled());
      s->disable();
    }
  }
  ~QuietOpenMesh() {
    std::cerr.rdbuf(cerrBuffer_);
    size_t i = 0;
    for (auto* s : {&::omerr(), &::omout(), &::omlog()}) {
      if (wasEnabled_[i++]) s->enable();
    }
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  std::ostringstream captured_;
  std::streambuf* cerrBuffer_;
  std::vector<bool> wasEnabled_;
};

// Reads `text` from memory (never a file: the same path serves files and
// bytes sent to the server). `binary`: a binary STL (OpenMesh's stream
// reader cannot tell by itself).
Status readWithOpenMesh(const std::string& name, const std::string& ext, const std::string& text, bool binary,
                        PolygonSoup& soup) {
  // IOManager and its reader modules are process-wide singletons with state
  // (the OBJ reader keeps materials and a path): one read at a time.
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  QuietOpenMesh quiet;
  SoupImporter importer(soup);
  OpenMesh::IO::Options options;
  if (binary) options += OpenMesh::IO::Options::Binary;
  bool ok = false;
  try {
    std::istringstream in(text, std::ios::in | std::ios::binary);
    ok = OpenMesh::IO::IOManager().read(in, ext, importer, options);
  } catch (const std::exception& e) {
    return parseError(name + ": malformed " + ext.substr(1) + " data (" + e.what() + ")");
  }
  if (!ok) return parseError(name + ": malformed or truncated " + ext.substr(1) + " data");
  return Status::ok();
}

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool isBinaryStl(const std::string& text) {
  // The size a binary STL's facet count implies (format_prescan.cc decides alike).
  uint32_t declared = 0;
  if (text.size() < 84) return false;
  std::memcpy(&declared, text.data() + 80, 4);
  return text.size() == 84 + 50 * static_cast<uint64_t>(declared);
}

Status checkExtension(const std::string& name, const std::string& ext) {
  const auto& supported = supportedImportExtensions();
  if (std::find(supported.begin(), supported.end(), ext) != supported.end()) return Status::ok();
  std::string list;
  for (const std::string& e : supported) list += (list.empty() ? "" : ", ") + e;
  return unsupported(name + ": unsupported file extension '" + ext + "' (supported: " + list + ")");
}

Status checkCounts(const PolygonSoup& soup, const PrescanCounts& counts, bool checkVertices, const std::string& src) {
  if (checkVertices && soup.points.size() != counts.vertices) {
    return parseError(src + ": the reader produced " + std::to_string(soup.points.size()) + " vertices, the file declares " +
                      std::to_string(counts.vertices) + " (malformed vertex data)");
  }
  if (static_cast<size_t>(soup.numFaces()) != counts.faces) {
    return parseError(src + ": the reader produced " + std::to_string(soup.numFaces()) + " faces, the file declares " +
                      std::to_string(counts.faces) + " (malformed face data, or faces with fewer than 3 vertices)");
  }
  return Status::ok();
}


Expected<BaseMesh> importText(const std::string& text, const std::string& ext, const std::string& name,
                              const ImportOptions& options, const std::string* gltfBaseDir) {
  const BuildOptions build{options.triangulate};
  if (ext == ".gltf" || ext == ".glb") {
    TESSERA_ASSIGN_OR_RETURN(GltfContent content, readGltf(name, text, gltfBaseDir));
    TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, buildBaseMesh(content.soup, build, name));
    TESSERA_RETURN_IF_ERROR(applyTags(content.tags, content.locate, mesh));
    return mesh;
  }

  PolygonSoup soup;
  PrescanCounts counts;
  if (ext == ".obj") {
    if (text.find('\0') != std::string::npos) return parseError(name + ": binary data, not a text OBJ file");
    TESSERA_RETURN_IF_ERROR(prescanObj(text, name, counts));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(name, ext, text, false, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, true, name));
  } else if (ext == ".off") {
    if (text.find('\0') != std::string::npos) return parseError(name + ": binary data, not a text OFF file");
    std::string normalised;
    TESSERA_RETURN_IF_ERROR(prescanOff(text, name, counts, normalised));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(name, ext, normalised, false, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, true, name));
  } else if (ext == ".ply") {
    TESSERA_RETURN_IF_ERROR(prescanPly(text, name, counts));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(name, ext, text, false, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, true, name));
  } else {  // .stl: vertices are merged by the reader, so only faces are counted
    TESSERA_RETURN_IF_ERROR(prescanStl(text, name, counts));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(name, ext, text, isBinaryStl(text), soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, false, name));
  }
  return buildBaseMesh(soup, build, name);
}

}  // namespace

const std::vector<std::string>& supportedImportExtensions() {
  static const std::vector<std::string> extensions = {".obj", ".off", ".ply", ".stl", ".gltf", ".glb"};
  return extensions;
}

Expected<BaseMesh> importMesh(const std::string& path, const ImportOptions& options) {
  const std::string ext = lowerCase(std::filesystem::path(path).extension().string());
  TESSERA_RETURN_IF_ERROR(checkExtension(path, ext));
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(path));
  // A .gltf may name buffers in files beside it.
  const std::string baseDir = std::filesystem::path(path).parent_path().string();
  return importText(text, ext, path, options, &baseDir);
}

Expected<BaseMesh> importMeshFromBytes(std::string_view bytes, const std::string& extension,
                                       const std::string& displayName, const ImportOptions& options) {
  std::string ext = lowerCase(extension);
  if (!ext.empty() && ext[0] != '.') ext.insert(0, ".");
  TESSERA_RETURN_IF_ERROR(checkExtension(displayName, ext));
  return importText(std::string(bytes), ext, displayName, options, nullptr);
}

}  // namespace tessera
