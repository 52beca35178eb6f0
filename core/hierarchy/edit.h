// Edits of a hierarchical document (Pulli & Lounsbery, "Hierarchical Editing
// and Rendering of Subdivision Surfaces" §2): vertex moves stored as
// offsets in local frames at any level, and sharpness tags at any level.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/util/vec3.h"

namespace tessera {

// Edits are numbered from 1 in the order they were made; ids never repeat.
struct EditId {
  uint64_t value = 0;
  friend bool operator==(EditId a, EditId b) { return a.value == b.value; }
  std::string toString() const { return "edit" + std::to_string(value); }
};

// A displacement of one control vertex at its level, in that vertex's local
// frame (local_frame.h) built from the coarser-level prediction, so that the
// detail follows later coarse edits (§2.3, §4.3).
struct VertexOffset {
  VertexId vertex;
  Vec3 localOffset;
};

// One user move: one or more vertices of one level moved together. A direct
// manipulation solves for the first vertex and moves the others by the same
// world displacement (§2.2); each is stored in its own frame.
struct MoveEdit {
  std::vector<VertexOffset> offsets;
};

// Sharpness set at a level; finer levels inherit it (decayed as usual) until
// overridden again (§2.4). Vertex sharpness 0 is smooth; > 0 makes a corner,
// or a cusp where no sharp edge meets the vertex.
struct EdgeSharpnessEdit {
  EdgeId edge;
  float sharpness = 0.0f;
};
struct VertexSharpnessEdit {
  VertexId vertex;
  float sharpness = 0.0f;
};

// docs/INTERPOLATION.md: the vertex becomes locally interpolating -- the surface passes
// through its control point -- with this tension (core/loop/ghost_ring.h), or
// stops being so. Later edits of the same vertex win, as for sharpness. It
// shapes the next level (the ghost ring), so it needs a level below its own.
struct InterpolationEdit {
  VertexId vertex;
  bool interpolating = true;
  double tension = 1.0;
  Vec3 tangent{0, 0, 0};  // boundary and crease vertices: the tangent line; zero: the default
};

struct Edit {
  EditId id;
  bool active = true;  // false once undone
  std::variant<MoveEdit, EdgeSharpnessEdit, VertexSharpnessEdit, InterpolationEdit> change;

  int level() const;
};

}  // namespace tessera
