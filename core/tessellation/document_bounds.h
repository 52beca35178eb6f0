// The document's bounds: whether a change keeps the surface inside the
// document's quantization grid (document_grid.h), the one rule by which a
// server, `tessera doc edit` and a replay all accept or refuse a command
// (docs/PROTOCOL.md "The document's bounds").
//
// The rule must be a function of the document's history alone: not of the
// levels a hierarchy happens to hold for its viewers, nor of a restart. So
// it reads only limits the edits themselves determine, the *bounded set*:
//
//   - every base vertex (level 0 is always held whole), and
//   - every vertex of level l >= 1 that an active edit of level l reaches
//     (SparseHierarchy::isReachedByEdit: a move or tag of it or of a ring
//     neighbour, or a sharpness on one of its edges). Such a vertex is held
//     with its complete ring whatever else is held, and its limit is exact.
//
// Limits of deeper levels that only a viewer made the hierarchy hold are
// never read. A command is accepted when every vertex of the bounded set
// whose limit it recomputed lies inside the grid; by induction from a base
// mesh inside the grid, every vertex of the bounded set then does.
#pragma once

#include <optional>
#include <span>

#include "core/document/document.h"
#include "core/document/edit_script.h"
#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "core/tessellation/quantization_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/util/status.h"

namespace tessera {

// Whether `id` belongs to the bounded set of `hierarchy` (false when the
// hierarchy does not hold it complete: then no edit reaches it).
bool inBoundedSet(const SparseHierarchy& hierarchy, VertexId id);

// Ok when every vertex of `recomputed` (limits a change recomputed, as in
// DirtySet::limits) that belongs to the bounded set has its limit inside
// `grid`. Otherwise kInvalidArgument naming the first such vertex, its limit
// and the grid's cube. Vertices the hierarchy no longer holds (a level an
// undo dropped) are skipped: no active edit reaches them.
Status checkWithinBounds(const SparseHierarchy& hierarchy, std::span<const VertexId> recomputed,
                         const QuantizationGrid& grid);

// Applies one edit-script command under the rule: refused, it is taken back
// and the document is as it was (`tessera doc edit`; a server does the same
// with its wire commands). A failed take-back is kInternal.
Status applyWithinBounds(const ScriptCommand& command, Document& document, const QuantizationGrid& grid);

// What the rule leaves open: a displayed vertex outside the bounded set can
// lie outside the grid where the surface bulges between the limits the rule
// reads (a sharp crease between two vertices pulled close to a face of the
// grid). Such a vertex is drawn on the grid's nearest face: `mesh` with its
// positions clamped onto the cube, so that its region can be encoded and
// its hash computed alike by a server and a viewer (docs/PROTOCOL.md "The
// document's bounds"). nullopt when every position is inside already.
std::optional<RegionMesh> clampedToGrid(const RegionMesh& mesh, const QuantizationGrid& grid);

}  // namespace tessera
