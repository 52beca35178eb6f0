// The control cage of one level, drawn as polygons between the control
// vertices the viewer shows (docs/VIEWER.md "The control cage"). The server
// sends the level's faces once (GetCage: topology only, which edits never
// change); each frame joins the ends of every edge of a face that turns its
// front to the eye, as the browser page does (docs/WEB_VIEWER.md "The
// control cage"). Pure functions, tested without a window.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "client/view/control_points.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"

namespace tessera::view {

struct ControlCage {
  int level = 0;
  uint64_t version = 0;                    // the document's when the server answered
  std::map<uint32_t, size_t> facesBySize;  // corners -> faces
  // Face f's corners are corners[faceStarts[f] .. faceStarts[f + 1]), packed
  // vertex ids at `level`, counter-clockwise seen from outside.
  std::vector<uint32_t> faceStarts{0};
  std::vector<uint64_t> corners;
  // Each edge once, its ends in increasing order, sorted; edgeFaces[i]: the
  // first two faces that have edge i (-1 for none).
  std::vector<std::pair<uint64_t, uint64_t>> edges;
  std::vector<std::array<int32_t, 2>> edgeFaces;

  size_t faces() const { return faceStarts.size() - 1; }
};

// Errors, naming the face: corners that do not add up to the vertices sent,
// a face of fewer than 3 corners, an index no id of that level can hold.
Expected<ControlCage> controlCageOf(const wire::Cage& reply);

// Two points per edge whose ends are both among `points` (sorted by id, as
// controlPoints gives them) and one of whose faces turns its front to the
// eye: the counter-clockwise side of the polygon of its shown corners (at
// least three), by Newell's normal, which takes a quad that is not flat. On
// a closed surface these are the edges one sees; it needs no normal, which a
// crease vertex has one of per side.
std::vector<V3> cageSegments(const ControlCage& cage, const std::vector<ControlPoint>& points, V3 eye);

}  // namespace tessera::view
