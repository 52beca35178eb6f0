#include "client/python/mesh_bytes.h"

#include <pybind11/pybind11.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "client/python/errors.h"
#include "client/python/offline_work.h"
#include "core/util/file_io.h"

namespace tessera::python {

wire::MeshFormat meshFormatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") return wire::MESH_FORMAT_OBJ;
  if (ext == ".off") return wire::MESH_FORMAT_OFF;
  if (ext == ".ply") return wire::MESH_FORMAT_PLY;
  if (ext == ".stl") return wire::MESH_FORMAT_STL;
  if (ext == ".glb") return wire::MESH_FORMAT_GLB;
  if (ext == ".usda") return wire::MESH_FORMAT_USDA;
  throw pybind11::value_error(path + ": not .obj, .off, .ply, .stl, .glb or .usda");
}

std::string offBytes(const std::vector<Vec3>& points, const PolygonSoup& faces) {
  const SurfaceMesh mesh = surfaceOf(points, faces, {});
  std::string path = (std::filesystem::temp_directory_path() / "tessera-python-XXXXXX.off").string();
  const int fd = mkstemps(path.data(), 4);
  if (fd < 0)
    throw Failure(
        ioError("cannot create a temporary file in " + std::filesystem::temp_directory_path().string()));
  ::close(fd);
  Status written = writeSurface(mesh, path, false);
  Expected<std::string> bytes = written.isOk() ? readFile(path) : Expected<std::string>(written);
  std::filesystem::remove(path);
  return valueOf(std::move(bytes));
}

}  // namespace tessera::python
