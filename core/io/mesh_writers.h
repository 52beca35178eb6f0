// The streaming writers of the indexed export formats (OBJ, OFF, PLY, STL),
// each straight from the SurfaceMesh to a FileWriter: no copy of the mesh,
// no file-sized string. Internal to core/io; exportMesh() chooses. The
// surface has been validated (mesh_export.h).
#pragma once

#include "core/io/file_writer.h"
#include "core/io/mesh_export.h"

namespace tessera::io_detail {

void writeObj(const SurfaceMesh& surface, FileWriter& out);
void writeOff(const SurfaceMesh& surface, FileWriter& out);
void writePly(const SurfaceMesh& surface, FileWriter& out);
void writeStl(const SurfaceMesh& surface, FileWriter& out);
// GLB without Draco, streamed (gltf_export.cc keeps the Draco form).
void writePlainGlb(const SurfaceMesh& surface, FileWriter& out);

}  // namespace tessera::io_detail
