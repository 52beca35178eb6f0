#include "core/tessellation/document_bounds.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

namespace tessera {

namespace {

std::string point(const Vec3& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", p[0], p[1], p[2]);
  return text;
}

// The vertex's local index when it belongs to the bounded set, else kNoIndex.
Index boundedVertex(const SparseHierarchy& hierarchy, VertexId id) {
  if (id.level() >= hierarchy.numLevels()) return kNoIndex;
  const Index v = hierarchy.level(id.level()).findVertex(id.index());
  if (v == kNoIndex) return kNoIndex;
  return id.level() == 0 || hierarchy.isReachedByEdit(id.level(), v) ? v : kNoIndex;
}

}  // namespace

bool inBoundedSet(const SparseHierarchy& hierarchy, VertexId id) {
  return boundedVertex(hierarchy, id) != kNoIndex;
}

Status checkWithinBounds(const SparseHierarchy& hierarchy, std::span<const VertexId> recomputed,
                         const QuantizationGrid& grid) {
  for (VertexId id : recomputed) {
    const Index v = boundedVertex(hierarchy, id);
    if (v == kNoIndex) continue;
    const Vec3& limit = hierarchy.limitPosition(id.level(), v);
    if (grid.contains(limit)) continue;
    return invalidArgument("the edit would move the surface outside the document's bounds: the limit of " +
                           id.toString() + " would be at " + point(limit) + ", outside the cube from " +
                           point(grid.origin) + " with side " + std::to_string(grid.range));
  }
  return Status::ok();
}

Status applyWithinBounds(const ScriptCommand& command, Document& document, const QuantizationGrid& grid) {
  // A remove cannot be taken back: keep the document to restore it.
  std::optional<Document> before;
  if (command.kind == ScriptCommand::Kind::kRemove) before = document;
  TESSERA_RETURN_IF_ERROR(applyScriptCommand(command, document));
  Status bounds = checkWithinBounds(document.hierarchy(), document.lastUpdate().limits, grid);
  if (bounds.isOk()) return bounds;
  if (before) {
    document = std::move(*before);
    return bounds;
  }
  Status back = takeBackScriptCommand(command, document);
  if (!back.isOk()) return internalError("taking back a refused command failed: " + back.message());
  return bounds;
}

std::optional<RegionMesh> clampedToGrid(const RegionMesh& mesh, const QuantizationGrid& grid) {
  const bool inside = std::all_of(mesh.positions.begin(), mesh.positions.end(),
                                  [&](const Vec3& p) { return grid.contains(p); });
  if (inside) return std::nullopt;
  RegionMesh clamped = mesh;
  for (Vec3& p : clamped.positions) {
    for (int k = 0; k < 3; ++k) p[k] = std::clamp(p[k], grid.origin[k], grid.origin[k] + grid.range);
  }
  return clamped;
}

}  // namespace tessera
