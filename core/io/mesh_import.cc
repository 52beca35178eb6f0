// Mesh import: the reader by extension, then the steps every format shares
// (see mesh_import.h for their order).
#include "core/io/mesh_import.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/io/gltf_import.h"
#include "core/io/tag_file.h"
#include "core/io/text_mesh_readers.h"
#include "core/mesh/crease_angle.h"
#include "core/mesh/mesh_validation.h"
#include "core/util/file_io.h"

namespace tessera {
namespace {

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// ".obj" from "obj", ".OBJ" or ".obj".
std::string dottedLowerCase(const std::string& extension) {
  std::string ext = lowerCase(extension);
  if (!ext.empty() && ext[0] != '.') ext.insert(0, ".");
  return ext;
}

Status checkExtension(const std::string& name, const std::string& ext) {
  const auto& supported = supportedImportExtensions();
  if (std::find(supported.begin(), supported.end(), ext) != supported.end()) return Status::ok();
  std::string list;
  for (const std::string& e : supported) list += (list.empty() ? "" : ", ") + e;
  return unsupported(name + ": unsupported file extension '" + ext + "' (supported: " + list + ")");
}

// "1 unused vertex", "2 unused vertices", "3 edges".
std::string plural(int n, std::string word) {
  if (n != 1) word = word.ends_with("vertex") ? word.substr(0, word.size() - 2) + "ices" : word + "s";
  return std::to_string(n) + " " + word;
}

// The steps after reading, in the order mesh_import.h gives; `gltfTags`
// are the tags a glTF states in `extras`, or null.
Expected<ImportedMesh> importRead(PolygonSoup soup, const std::string& name, const ImportOptions& options,
                                  const GltfContent* gltfTags) {
  ImportReport report;
  if (options.dropUnused) report.renumbering = dropUnusedVertices(soup);
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, buildBaseMesh(soup, BuildOptions{options.triangulate}, name));
  if (options.creaseAngle >= 0) {
    auto creased = creaseByDihedralAngle(soup, options.creaseAngle, mesh);
    if (!creased.isOk()) return creased.status().withContext(name);
    report.edgesCreasedByAngle = *creased;
  }
  // Tags in the file itself win over the crease angle: they are explicit.
  if (gltfTags)
    TESSERA_RETURN_IF_ERROR(applyTags(gltfTags->tags, gltfTags->locate, mesh, report.renumbering));
  if (!soup.tags.empty()) {
    TESSERA_RETURN_IF_ERROR(applyTags(featureTagsOf(soup.tags), name, mesh, report.renumbering));
    report.tagsInFile = static_cast<int>(soup.tags.size());
  }
  report.boundary = soup.boundary;
  report.creaseMethod = soup.creaseMethod;
  report.scheme = soup.scheme;
  return ImportedMesh{std::move(mesh), std::move(report)};
}

Expected<ImportedMesh> importText(std::string_view text, const std::string& ext, const std::string& name,
                                  const ImportOptions& options, const std::string* gltfBaseDir) {
  PolygonSoup soup;
  if (ext == ".gltf" || ext == ".glb") {
    TESSERA_ASSIGN_OR_RETURN(GltfContent gltf, readGltf(name, std::string(text), gltfBaseDir));
    return importRead(std::move(gltf.soup), name, options, &gltf);
  }
  if (ext == ".obj") {
    TESSERA_RETURN_IF_ERROR(io_detail::readObj(text, name, soup));
  } else if (ext == ".off") {
    TESSERA_RETURN_IF_ERROR(io_detail::readOff(text, name, soup));
  } else if (ext == ".ply") {
    TESSERA_RETURN_IF_ERROR(io_detail::readPly(text, name, soup));
  } else if (ext == ".usda") {
    TESSERA_RETURN_IF_ERROR(io_detail::readUsda(text, name, soup, {.usdPrim = options.usdPrim}));
  } else {
    TESSERA_RETURN_IF_ERROR(io_detail::readStl(text, name, soup));
  }
  return importRead(std::move(soup), name, options, nullptr);
}

}  // namespace

std::string describeImport(const ImportReport& report, const ImportOptions& options) {
  std::string text;
  const auto add = [&text](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (options.dropUnused && report.renumbering.dropped > 0) {
    add("dropped " + plural(report.renumbering.dropped, "unused vertex") + " (--drop-unused)");
  }
  if (options.creaseAngle >= 0) {
    char degrees[32];
    std::snprintf(degrees, sizeof degrees, "%g", options.creaseAngle);
    add("creased " + plural(report.edgesCreasedByAngle, "edge") + " sharper than " + degrees +
        " degrees (--crease-angle)");
  }
  if (report.tagsInFile > 0)
    add("applied " + plural(report.tagsInFile, "tag") + " the file states (t crease, t corner)");
  return text;
}

const std::vector<std::string>& supportedImportExtensions() {
  static const std::vector<std::string> extensions = {".obj",  ".off", ".ply", ".stl",
                                                      ".gltf", ".glb", ".usda"};
  return extensions;
}

Expected<ImportedMesh> importMeshWithReport(const std::string& path, const ImportOptions& options) {
  const std::string ext = lowerCase(std::filesystem::path(path).extension().string());
  TESSERA_RETURN_IF_ERROR(checkExtension(path, ext));
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(path));
  // A .gltf may name buffers in files beside it.
  const std::string baseDir = std::filesystem::path(path).parent_path().string();
  return importText(text, ext, path, options, &baseDir);
}

Expected<ImportedMesh> importMeshFromBytesWithReport(std::string_view bytes, const std::string& extension,
                                                     const std::string& displayName,
                                                     const ImportOptions& options) {
  const std::string ext = dottedLowerCase(extension);
  TESSERA_RETURN_IF_ERROR(checkExtension(displayName, ext));
  return importText(bytes, ext, displayName, options, nullptr);
}

bool readsPolygonSoup(const std::string& extension) {
  const std::string ext = dottedLowerCase(extension);
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".usda";
}

Expected<ImportedMesh> importSoupWithReport(PolygonSoup soup, const std::string& displayName,
                                            const ImportOptions& options) {
  return importRead(std::move(soup), displayName, options, nullptr);
}

Expected<PolygonSoup> importPolygonSoup(std::string_view bytes, const std::string& extension,
                                        const std::string& displayName, const std::string& usdPrim) {
  const std::string ext = dottedLowerCase(extension);
  const io_detail::TextReadOptions checked{.checkIndices = true, .usdPrim = usdPrim};
  PolygonSoup soup;
  if (ext == ".obj") {
    TESSERA_RETURN_IF_ERROR(io_detail::readObj(bytes, displayName, soup, checked));
  } else if (ext == ".off") {
    TESSERA_RETURN_IF_ERROR(io_detail::readOff(bytes, displayName, soup, checked));
  } else if (ext == ".ply") {
    TESSERA_RETURN_IF_ERROR(io_detail::readPly(bytes, displayName, soup, checked));
  } else if (ext == ".usda") {
    TESSERA_RETURN_IF_ERROR(io_detail::readUsda(bytes, displayName, soup, checked));
  } else {
    return unsupported(displayName + ": polygons are read from .obj, .off, .ply and .usda files, not '" +
                       ext + "'");
  }
  if (soup.points.empty()) return parseError(displayName + ": no vertices");
  if (soup.numFaces() == 0) return parseError(displayName + ": no faces");
  return soup;
}

Expected<BaseMesh> importMesh(const std::string& path, const ImportOptions& options) {
  TESSERA_ASSIGN_OR_RETURN(ImportedMesh imported, importMeshWithReport(path, options));
  return std::move(imported.mesh);
}

Expected<BaseMesh> importMeshFromBytes(std::string_view bytes, const std::string& extension,
                                       const std::string& displayName, const ImportOptions& options) {
  TESSERA_ASSIGN_OR_RETURN(ImportedMesh imported,
                           importMeshFromBytesWithReport(bytes, extension, displayName, options));
  return std::move(imported.mesh);
}

}  // namespace tessera
