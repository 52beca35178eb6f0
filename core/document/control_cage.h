// The control cage of one level: the level's faces over its vertices'
// canonical indices, which a viewer draws as polygons between the control
// vertices it shows (docs/PROTOCOL.md section 17). A Catmull-Clark base
// keeps its n-gons and every finer level is quads (core/catmark/quad_split.h);
// a Loop level is triangles. Only topology: the positions are the viewer's
// (limit positions from the regions it holds), so a cage is fetched once per
// level and stays valid across edits, which never change a level's faces.
#pragma once

#include <cstdint>
#include <vector>

#include "core/document/document.h"
#include "core/util/status.h"

namespace tessera {

struct ControlCage {
  int level = 0;
  std::vector<uint32_t> faceSizes;  // corners of face k
  std::vector<uint64_t> vertices;   // the corners, face after face, counter-clockwise: indices at `level`
};

// Errors: a level outside 0..maxLevel, or beyond what Document::evaluate
// holds, naming the level. A caller with a tighter bound checks
// doc.counts().faces(level) first: nothing is evaluated before that.
Expected<ControlCage> controlCage(const Document& doc, int level);

}  // namespace tessera
