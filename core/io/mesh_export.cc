#include "core/io/mesh_export.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "core/io/draco_encode.h"
#include "core/io/export_common.h"
#include "core/io/gltf_export.h"
#include "core/io/mesh_writers.h"
#include "core/io/usda_writer.h"

namespace tessera {
namespace {

enum class ExportFormat { kObj, kOff, kPly, kStl, kGlb, kUsda };

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

Expected<ExportFormat> formatFor(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return ExportFormat::kObj;
  if (ext == ".off") return ExportFormat::kOff;
  if (ext == ".ply") return ExportFormat::kPly;
  if (ext == ".stl") return ExportFormat::kStl;
  if (ext == ".glb") return ExportFormat::kGlb;
  if (ext == ".usda") return ExportFormat::kUsda;
  std::string supported;
  for (const std::string& s : supportedExportExtensions()) supported += (supported.empty() ? "" : ", ") + s;
  return unsupported("cannot export to '" + (ext.empty() ? std::string("(no extension)") : ext) +
                     "' (supported: " + supported + ")");
}

std::string formatVec(const Vec3& v) {
  char buffer[128];
  const int n = std::snprintf(buffer, sizeof buffer, "(%g, %g, %g)", v[0], v[1], v[2]);
  return std::string(buffer, static_cast<std::size_t>(std::max(n, 0)));
}

}  // namespace

namespace io_detail {

Status writeFileBytes(const std::string& path, const char* data, std::size_t size) {
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) return ioError(path + ": cannot open for writing: " + std::strerror(errno));
  if (size > 0 && std::fwrite(data, 1, size, file.get()) != size) {
    return ioError(path + ": write failed: " + std::strerror(errno));
  }
  // fclose flushes; a full disk often shows up only here.
  if (std::fclose(file.release()) != 0) return ioError(path + ": write failed: " + std::strerror(errno));
  return Status::ok();
}

}  // namespace io_detail

bool exportKeepsPolygons(const std::string& path) {
  const Expected<ExportFormat> format = formatFor(path);
  return format.isOk() && (*format == ExportFormat::kObj || *format == ExportFormat::kOff ||
                           *format == ExportFormat::kPly || *format == ExportFormat::kUsda);
}

bool exportStatesScheme(const std::string& path) {
  const Expected<ExportFormat> format = formatFor(path);
  return format.isOk() && *format == ExportFormat::kUsda;
}

const std::vector<std::string>& supportedExportExtensions() {
  static const std::vector<std::string> kExtensions = {".obj", ".off", ".ply", ".stl", ".glb", ".usda"};
  return kExtensions;
}

Status validateSurfaceMesh(const SurfaceMesh& surface) {
  const std::size_t n = surface.positions.size();
  if (surface.triangles.empty()) return invalidMesh("surface has no triangles");
  if (!surface.normals.empty() && surface.normals.size() != n) {
    return invalidMesh("surface has " + std::to_string(surface.normals.size()) + " normals for " +
                       std::to_string(n) + " positions (expected one per position, or none)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!isFinite(surface.positions[i])) {
      return invalidMesh("position " + std::to_string(i) + " is not finite " +
                         formatVec(surface.positions[i]));
    }
  }
  for (std::size_t i = 0; i < surface.normals.size(); ++i) {
    const Vec3& normal = surface.normals[i];
    if (!isFinite(normal))
      return invalidMesh("normal " + std::to_string(i) + " is not finite " + formatVec(normal));
    // Zero normals cannot be made unit length, which glTF requires.
    if (normal.sqrnorm() == 0.0) return invalidMesh("normal " + std::to_string(i) + " is zero");
  }
  if (!surface.polygonOffsets.empty()) {
    const auto& offsets = surface.polygonOffsets;
    if (offsets.front() != 0 || static_cast<std::size_t>(offsets.back()) != surface.polygonCorners.size())
      return invalidMesh("polygon offsets do not span the " + std::to_string(surface.polygonCorners.size()) +
                         " polygon corners");
    for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
      const int corners = offsets[f + 1] - offsets[f];
      // PLY counts a face's corners in one byte.
      if (corners < 3 || corners > 255)
        return invalidMesh("polygon " + std::to_string(f) + " has " + std::to_string(corners) +
                           " corners (3 to 255)");
      for (int c = offsets[f]; c < offsets[f + 1]; ++c) {
        const int v = surface.polygonCorners[static_cast<std::size_t>(c)];
        if (v < 0 || static_cast<std::size_t>(v) >= n)
          return invalidMesh("polygon " + std::to_string(f) + " corner " + std::to_string(c - offsets[f]) +
                             ": vertex index " + std::to_string(v) + " outside [0, " + std::to_string(n) +
                             ")");
      }
    }
  }
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = surface.triangles[f][c];
      if (v < 0 || static_cast<std::size_t>(v) >= n) {
        return invalidMesh("triangle " + std::to_string(f) + " corner " + std::to_string(c) +
                           ": vertex index " + std::to_string(v) + " outside [0, " + std::to_string(n) + ")");
      }
    }
  }
  return Status::ok();
}

Status exportMesh(const SurfaceMesh& surface, const std::string& path, const ExportOptions& options) {
  const Expected<ExportFormat> formatOr = formatFor(path);
  if (!formatOr) return formatOr.status().withContext(path);
  const ExportFormat format = *formatOr;
  if (options.draco && format != ExportFormat::kGlb) {
    return unsupported(path + ": Draco compression is only available for .glb");
  }
  if (options.draco) {
    const Status status = io_detail::validateDracoOptions(options);
    if (!status.isOk()) return status.withContext(path);
  }
  if (const Status status = validateSurfaceMesh(surface); !status.isOk()) return status.withContext(path);

  if (format == ExportFormat::kGlb && options.draco) {
    const Status status = io_detail::writeGlb(surface, path, options);
    // writeGlb's I/O errors already name the path.
    return status.isOk() || status.code() == ErrorCode::kIoError ? status : status.withContext(path);
  }
  TESSERA_ASSIGN_OR_RETURN(io_detail::FileWriter out, io_detail::FileWriter::open(path));
  switch (format) {
    case ExportFormat::kObj:
      io_detail::writeObj(surface, out);
      break;
    case ExportFormat::kOff:
      io_detail::writeOff(surface, out);
      break;
    case ExportFormat::kPly:
      io_detail::writePly(surface, out);
      break;
    case ExportFormat::kStl:
      io_detail::writeStl(surface, out);
      break;
    case ExportFormat::kGlb:
      io_detail::writePlainGlb(surface, out);
      break;
    case ExportFormat::kUsda:
      io_detail::writeUsda(surface, out);
      break;
  }
  return out.close();
  return internalError(path + ": unhandled export format");
}

}  // namespace tessera
