// Feature-tag sidecar files (`--tags FILE`). One tag per line, `#` starts a
// comment, indices are 0-based:
//   crease I J SHARPNESS   edge between vertices I and J; SHARPNESS float or `inf`
//   corner I SHARPNESS     vertex sharpness (a corner, or a cusp where no sharp
//                          edge meets the vertex)
// Errors carry the file name and line number. A second tag on the same edge
// or vertex is an error naming both lines (a silent "last wins" would hide
// authoring mistakes). See docs/FORMATS.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/mesh/unused_vertices.h"
#include "core/util/status.h"

namespace tessera {

struct FeatureTag {
  enum class Kind { kCrease, kCorner };
  Kind kind = Kind::kCrease;
  int v0 = -1;
  int v1 = -1;  // crease only
  float sharpness = 0.0f;
  int line = 0;  // 1-based source line, for error messages
};

Expected<std::vector<FeatureTag>> parseTags(const std::string& text, const std::string& sourceName);

// The tags a mesh file states itself (OBJ's `t crease` and `t corner`,
// core/mesh/polygon_soup.h), as tags to apply, with their lines.
std::vector<FeatureTag> featureTagsOf(const std::vector<SoupTag>& tags);

// Applies tags to the mesh; a tag naming a missing edge or vertex is an error
// with its line number, and leaves the mesh unchanged. Tags name vertices by
// the file's numbers: after --drop-unused, `renumbering` maps them to the
// mesh's (a tag naming a dropped vertex is an error naming it), and messages
// keep the file's numbers.
Status applyTags(const std::vector<FeatureTag>& tags, const std::string& sourceName, BaseMesh& mesh,
                 const VertexRenumbering& renumbering = VertexRenumbering{});

// Same, for tags from another source (glTF extras): `locate` names a tag in
// error messages, e.g. "model.glb: extras.tessera.creases[2]".
using TagLocator = std::function<std::string(const FeatureTag&)>;
Status applyTags(const std::vector<FeatureTag>& tags, const TagLocator& locate, BaseMesh& mesh,
                 const VertexRenumbering& renumbering = VertexRenumbering{});

// What the tag applier needs of a mesh, so that one applier serves the
// triangle mesh (BaseMesh) and the polygon meshes of core/schemes.
struct TagTarget {
  int numVertices = 0;
  std::function<bool(int, int)> hasEdge;         // whether two of the mesh's vertices share an edge
  std::function<Status(const FeatureTag&)> set;  // sets a checked tag, its vertices the mesh's
};

// How errors name a tag: every message about a tag starts with prefix(tag)
// ("t.tags:3: crease 0 4: "), and a duplicate names the tag it repeats by
// reference(tag) ("t.tags:1").
struct TagNaming {
  TagLocator prefix;
  TagLocator reference;
};

// The applier behind the overloads above: checks every tag first (its
// vertices exist, or were dropped, by `renumbering`; its sharpness; a
// crease's edge; no second tag on an edge or vertex), then sets them in
// order, so an error leaves the mesh unchanged.
Status applyTags(const std::vector<FeatureTag>& tags, const TagNaming& naming, const TagTarget& target,
                 const VertexRenumbering& renumbering = VertexRenumbering{});

// Parses a sharpness token: a finite number >= 0 or `inf` (any case).
// Returns false for anything else (negative, NaN, junk).
bool parseSharpness(const std::string& token, float& sharpness);

// Reads, parses and applies the file.
Status applyTagFile(const std::string& path, BaseMesh& mesh,
                    const VertexRenumbering& renumbering = VertexRenumbering{});

}  // namespace tessera
