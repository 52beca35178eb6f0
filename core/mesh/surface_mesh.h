// A refined or limit surface as plain arrays: what refinement, evaluation and
// tessellation produce and what every exporter and codec consumes. It lives
// with the base mesh, below both, so producing a surface never means
// including an exporter.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace tessera {

struct SurfaceMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;                  // empty, or one unit normal per position
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
  // A surface of polygons (a quad scheme's or Doo-Sabin's refinement) also
  // keeps its faces: face f's corners, counter-clockwise, are
  // polygonCorners[polygonOffsets[f] .. polygonOffsets[f + 1]). `triangles`
  // is then their fan triangulation, for the formats and consumers that take
  // triangles only. Both empty for a surface of triangles.
  std::vector<int> polygonOffsets, polygonCorners;

  // A subdivision cage's sharp features, for the formats that carry them
  // (OBJ's `t` lines in OpenSubdiv's dialect, docs/FORMATS.md): creases by
  // their two vertices and corners by theirs, with their sharpness; and the
  // cage's options ("edge-only" or "edge-and-corner", "uniform" or
  // "chaikin"). Empty for a surface that is no cage (a limit surface).
  struct Crease {
    int v0 = 0, v1 = 0;
    float sharpness = 0;
  };
  struct Corner {
    int v = 0;
    float sharpness = 0;
  };
  std::vector<Crease> creases;
  std::vector<Corner> corners;
  std::string boundary, creaseMethod;
  // The cage's subdivision scheme ("loop", "catmull-clark", "bilinear"), for
  // the formats that state it (USD's subdivisionScheme); empty for a
  // surface that is no cage.
  std::string scheme;

  size_t numPolygons() const { return polygonOffsets.empty() ? 0 : polygonOffsets.size() - 1; }
  // Appends a polygon and its fan of triangles.
  void addPolygon(std::span<const int> corners) {
    if (polygonOffsets.empty()) polygonOffsets.push_back(0);
    polygonCorners.insert(polygonCorners.end(), corners.begin(), corners.end());
    polygonOffsets.push_back(static_cast<int>(polygonCorners.size()));
    for (size_t k = 1; k + 1 < corners.size(); ++k)
      triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
};

}  // namespace tessera
