// PolygonSoup: what a file reader produces before any validation -- points and
// polygons as raw indices, exactly as the file stated them. buildBaseMesh()
// (mesh_validation.h) is the only way from a soup to a BaseMesh.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace tessera {

// A sharp feature the file states with its mesh (OBJ's `t crease` and
// `t corner` in OpenSubdiv's dialect, docs/FORMATS.md): a crease on the
// edge v0-v1, or a corner on v0, by the file's 0-based vertex numbers.
struct SoupTag {
  bool crease = true;
  int v0 = -1, v1 = -1;
  float sharpness = 0;
  int line = 0;  // 1-based, for messages
};

// How many of the faces `faceOffsets` delimits have other than three
// corners: a mesh with any is a Catmull-Clark document unless asked otherwise
// (docs/ARCHITECTURE.md, "Catmull-Clark documents").
inline int countFacesNotTriangles(std::span<const int> faceOffsets) {
  int n = 0;
  for (std::size_t f = 0; f + 1 < faceOffsets.size(); ++f) n += faceOffsets[f + 1] - faceOffsets[f] != 3;
  return n;
}

struct PolygonSoup {
  std::vector<Vec3> points;
  // Face i uses indices[faceOffsets[i] .. faceOffsets[i+1]); faceOffsets has
  // numFaces()+1 entries (a single 0 when there are no faces).
  std::vector<int> faceOffsets{0};
  std::vector<int> indices;

  // Subdivision tags the file states, and its options (OBJ's
  // `t interpolateboundary` and `t creasemethod`, named as the command line
  // names them: "edge-only" or "edge-and-corner", "uniform" or "chaikin";
  // empty when the file does not say).
  std::vector<SoupTag> tags;
  std::string boundary, creaseMethod;
  // The subdivision scheme the file states (USD's `subdivisionScheme`):
  // "loop", "catmull-clark", "bilinear", or "none" for a polygon mesh that
  // is not to be subdivided; empty when the format cannot say (OBJ, OFF, PLY).
  std::string scheme;

  int numFaces() const { return static_cast<int>(faceOffsets.size()) - 1; }
  void addFace(const std::vector<int>& face) {
    indices.insert(indices.end(), face.begin(), face.end());
    faceOffsets.push_back(static_cast<int>(indices.size()));
  }
};

}  // namespace tessera
