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

namespace tessera {
namespace {

enum class ExportFormat { kObj, kPly, kGlb };

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

Expected<ExportFormat> formatFor(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return ExportFormat::kObj;
  if (ext == ".ply") return ExportFormat::kPly;
  if (ext == ".glb") return ExportFormat::kGlb;
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

// ---- OBJ -------------------------------------------------------------------

// std::to_chars without a precision prints the shortest text that parses back
// to the same double, so OBJ output round-trips exactly.
void appendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void appendLine(std::string& out, const char* tag, const Vec3& v) {
  out += tag;
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    appendNumber(out, v[k]);
  }
  out += '\n';
}

std::string encodeObj(const SurfaceMesh& surface) {
  std::string out = "# Tessera surface export\n";
  out.reserve(surface.positions.size() * 120 + surface.triangles.size() * 40);
  for (const Vec3& p : surface.positions) appendLine(out, "v", p);
  for (const Vec3& n : surface.normals) appendLine(out, "vn", n);
  const bool withNormals = !surface.normals.empty();
  char buffer[24];
  for (const auto& t : surface.triangles) {
    out += 'f';
    for (int v : t) {
      // OBJ indices are 1-based; `a//a` names position a and normal a.
      const auto end = std::to_chars(buffer, buffer + sizeof buffer, v + 1).ptr;
      out += ' ';
      out.append(buffer, end);
      if (withNormals) {
        out += "//";
        out.append(buffer, end);
      }
    }
    out += '\n';
  }
  return out;
}

// ---- PLY -------------------------------------------------------------------

// Binary PLY is little-endian by declaration, whatever the host.
template <typename T>
void appendLittleEndian(std::string& out, T value) {
  static_assert(sizeof(T) == 4);
  const auto bits = std::bit_cast<std::uint32_t>(value);
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((bits >> shift) & 0xffu);
}

std::string encodePly(const SurfaceMesh& surface) {
  const bool withNormals = !surface.normals.empty();
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment Tessera surface export\n";
  out += "element vertex " + std::to_string(surface.positions.size()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  if (withNormals) out += "property float nx\nproperty float ny\nproperty float nz\n";
  out += "element face " + std::to_string(surface.triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";

  out.reserve(out.size() + surface.positions.size() * (withNormals ? 24 : 12) + surface.triangles.size() * 13);
  for (std::size_t i = 0; i < surface.positions.size(); ++i) {
    for (float c : io_detail::toFloat3(surface.positions[i])) appendLittleEndian(out, c);
    if (withNormals) {
      for (float c : io_detail::toFloat3(surface.normals[i])) appendLittleEndian(out, c);
    }
  }
  for (const auto& t : surface.triangles) {
    out += static_cast<char>(3);
    for (int v : t) appendLittleEndian(out, static_cast<std::int32_t>(v));
  }
  return out;
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

const std::vector<std::string>& supportedExportExtensions() {
  static const std::vector<std::string> kExtensions = {".obj", ".ply", ".glb"};
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
      return invalidMesh("position " + std::to_string(i) + " is not finite " + formatVec(surface.positions[i]));
    }
  }
  for (std::size_t i = 0; i < surface.normals.size(); ++i) {
    const Vec3& normal = surface.normals[i];
    if (!isFinite(normal)) return invalidMesh("normal " + std::to_string(i) + " is not finite " + formatVec(normal));
    // Zero normals cannot be made unit length, which glTF requires.
    if (normal.sqrnorm() == 0.0) return invalidMesh("normal " + std::to_string(i) + " is zero");
  }
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = surface.triangles[f][c];
      if (v < 0 || static_cast<std::size_t>(v) >= n) {
        return invalidMesh("triangle " + std::to_string(f) + " corner " + std::to_string(c) + ": vertex index " +
                           std::to_string(v) + " outside [0, " + std::to_string(n) + ")");
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

  switch (format) {
    case ExportFormat::kObj: {
      const std::string text = encodeObj(surface);
      return io_detail::writeFileBytes(path, text.data(), text.size());
    }
    case ExportFormat::kPly: {
      const std::string bytes = encodePly(surface);
      return io_detail::writeFileBytes(path, bytes.data(), bytes.size());
    }
    case ExportFormat::kGlb: {
      const Status status = io_detail::writeGlb(surface, path, options);
      // writeGlb's I/O errors already name the path.
      return status.isOk() || status.code() == ErrorCode::kIoError ? status : status.withContext(path);
    }
  }
  return internalError(path + ": unhandled export format");
}

}  // namespace tessera
