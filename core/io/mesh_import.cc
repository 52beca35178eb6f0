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

Status readWithOpenMesh(const std::string& path, const std::string& ext, const std::string* text,
                        PolygonSoup& soup) {
  // IOManager and its reader modules are process-wide singletons with state
  // (the OBJ reader keeps materials and a path): one read at a time.
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  QuietOpenMesh quiet;
  SoupImporter importer(soup);
  OpenMesh::IO::Options options;
  bool ok = false;
  try {
    if (text != nullptr) {
      std::istringstream in(*text);
      ok = OpenMesh::IO::IOManager().read(in, ext, importer, options);
    } else {
      ok = OpenMesh::IO::IOManager().read(path, importer, options);
    }
  } catch (const std::exception& e) {
    return parseError(path + ": malformed " + ext.substr(1) + " data (" + e.what() + ")");
  }
  if (!ok) return parseError(path + ": malformed or truncated " + ext.substr(1) + " data");
  return Status::ok();
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
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

}  // namespace

const std::vector<std::string>& supportedImportExtensions() {
  static const std::vector<std::string> extensions = {".obj", ".off", ".ply", ".stl", ".gltf", ".glb"};
  return extensions;
}

Expected<BaseMesh> importMesh(const std::string& path, const ImportOptions& options) {
  const std::string ext = lowerExtension(path);
  const auto& supported = supportedImportExtensions();
  if (std::find(supported.begin(), supported.end(), ext) == supported.end()) {
    std::string list;
    for (const std::string& e : supported) list += (list.empty() ? "" : ", ") + e;
    return unsupported(path + ": unsupported file extension '" + ext + "' (supported: " + list + ")");
  }
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(path));
  const BuildOptions build{options.triangulate};

  if (ext == ".gltf" || ext == ".glb") {
    TESSERA_ASSIGN_OR_RETURN(GltfContent content, readGltf(path, text));
    TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, buildBaseMesh(content.soup, build, path));
    TESSERA_RETURN_IF_ERROR(applyTags(content.tags, content.locate, mesh));
    return mesh;
  }

  PolygonSoup soup;
  PrescanCounts counts;
  if (ext == ".obj") {
    if (text.find('\0') != std::string::npos) return parseError(path + ": binary data, not a text OBJ file");
    TESSERA_RETURN_IF_ERROR(prescanObj(text, path, counts));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(path, ext, nullptr, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, true, path));
  } else if (ext == ".off") {
    if (text.find('\0') != std::string::npos) return parseError(path + ": binary data, not a text OFF file");
    std::string normalised;
    TESSERA_RETURN_IF_ERROR(prescanOff(text, path, counts, normalised));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(path, ext, &normalised, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, true, path));
  } else if (ext == ".ply") {
    TESSERA_RETURN_IF_ERROR(prescanPly(text, path, counts));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(path, ext, nullptr, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, true, path));
  } else {  // .stl: vertices are merged by the reader, so only faces are counted
    TESSERA_RETURN_IF_ERROR(prescanStl(text, path, counts));
    TESSERA_RETURN_IF_ERROR(readWithOpenMesh(path, ext, nullptr, soup));
    TESSERA_RETURN_IF_ERROR(checkCounts(soup, counts, false, path));
  }
  return buildBaseMesh(soup, build, path);
}

}  // namespace tessera
