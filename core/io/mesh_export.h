// Export of a refined or limit surface to OBJ, OFF, PLY, STL, glTF 2.0 GLB or USDA,
// optionally Draco-compressed via KHR_draco_mesh_compression (GLB only).
// Every format is streamed to its file (mesh_writers.h): memory stays that
// of the surface, whatever the file's size.
// The format follows the extension of the output path, case-insensitively:
// OBJ, OFF and PLY write a surface's polygons where it has them (a quad
// scheme's refinement: quads), its triangles otherwise; STL and GLB always
// write triangles, as their formats require.
//   .obj  text; `v`, `vn` when normals are present, faces `f a//a b//b c//c`.
//         Coordinates are printed as the shortest decimal that reads back to
//         the same double, so OBJ (and OFF) are the lossless formats.
//   .off  text OFF; positions as in OBJ, faces `3 a b c` (0-based). OFF has
//         no normals.
//   .ply  binary little-endian PLY 1.0, float32 x y z (and nx ny nz), faces as
//         `list uchar int`. Binary rather than ASCII: about a third of the
//         size, no float printing or parsing, and float32 is what every PLY
//         reader (OpenMesh, MeshLab, Blender) accepts.
//   .stl  binary STL: float32 corners and each facet's own unit normal
//         (STL has no vertex normals or indices).
//   .glb  glTF 2.0 binary, float32 POSITION (with min/max) and unit NORMAL,
//         16-bit indices when every index fits, 32-bit otherwise. With
//         `draco`, the primitive is stored only in Draco form, so
//         KHR_draco_mesh_compression is listed in extensionsRequired.
//   .usda USD's text format, one Mesh prim: its polygons, and a cage's
//         scheme and tags or a limit surface's vertex normals (usda_writer.h).
//
// Errors, all naming the file and the offending element:
//   unsupported      the extension is none of the above, or `draco` is set
//                    for a format other than .glb;
//   invalidArgument  Draco options out of range;
//   invalidMesh      no triangles, an index out of range, a non-finite
//                    position or normal, a zero normal, a normals count
//                    that is neither 0 nor the positions count, or polygons
//                    whose offsets do not span their corners or that have
//                    fewer than 3 or more than 255 corners;
//   ioError          the file cannot be written.
// Nothing is written unless the input is valid.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

struct ExportOptions {
  bool draco = false;  // GLB only: KHR_draco_mesh_compression
  // Quantization of positions, 1..30 bits. Draco quantizes each coordinate on
  // a uniform grid spanning the largest bounding-box extent, so every decoded
  // coordinate is within maxExtent / (2^bits - 1) of the input (half a step
  // in theory; one whole step is the bound the tests check).
  int dracoPositionBits = 16;
  int dracoNormalBits = 12;       // octahedral quantization of normals, 2..30
  int dracoCompressionLevel = 7;  // 0 (fastest) .. 10 (smallest); Draco speed = 10 - level
};

Status exportMesh(const SurfaceMesh& surface, const std::string& path, const ExportOptions& options = {});

// Checks what exportMesh checks before writing (see above), for any format.
Status validateSurfaceMesh(const SurfaceMesh& surface);

// Whether exportMesh() writes a polygon surface's polygons to `path` (OBJ,
// OFF, PLY) rather than its triangles.
bool exportKeepsPolygons(const std::string& path);

// Whether the format of `path` states a cage's subdivision scheme and tags
// beside its polygons (USD's subdivisionScheme); OBJ's `t` lines state tags only.
bool exportStatesScheme(const std::string& path);

// Extensions exportMesh() accepts, lower case with the dot: ".obj", ...
const std::vector<std::string>& supportedExportExtensions();

}  // namespace tessera
