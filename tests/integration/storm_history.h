// The editing storm of the durability test and soak (docs/STORE.md "Kill -9 soak"), and the
// local replay of what the server acknowledged.
//
// A StormCommand is one command an editor sends: a move of a control vertex
// by a signed offset, an edge's sharpness (smooth, semi-sharp or infinite),
// or an undo or redo of one of that editor's acknowledged edits. It turns
// into the wire message the server gets and applies to a local Document as
// the server's DocumentHost applies it.
//
// settledStateKey() names a replayed Document by everything that decides
// what it shows now and after any later command of the storm, so that
// candidate histories the checker cannot tell apart are kept once each.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <variant>

#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/mesh/sharpness.h"
#include "protocol/tessera.pb.h"

namespace tessera::testing {

struct StormCommand {
  enum class Kind { kMove, kCrease, kUndo, kRedo };
  Kind kind = Kind::kMove;
  VertexId vertex;      // kMove
  Vec3 displacement;    // kMove, in world units
  EdgeId edge;          // kCrease
  float sharpness = 0;  // kCrease
  uint64_t target = 0;  // kUndo, kRedo: an acknowledged edit id

  wire::ClientMessage message(uint64_t documentId) const {
    wire::ClientMessage m;
    switch (kind) {
      case Kind::kMove: {
        auto* v = m.mutable_move_vertex();
        v->set_document_id(documentId);
        v->add_vertex_ids(vertex.packed());
        v->mutable_target()->set_x(displacement[0]);
        v->mutable_target()->set_y(displacement[1]);
        v->mutable_target()->set_z(displacement[2]);
        v->set_mode(wire::MOVE_MODE_OFFSET);
        break;
      }
      case Kind::kCrease:
        m.mutable_set_edge_sharpness()->set_document_id(documentId);
        m.mutable_set_edge_sharpness()->set_edge_id(edge.packed());
        m.mutable_set_edge_sharpness()->set_sharpness(sharpness);
        break;
      case Kind::kUndo:
        m.mutable_undo()->set_document_id(documentId);
        m.mutable_undo()->set_edit_id(target);
        break;
      case Kind::kRedo:
        m.mutable_redo()->set_document_id(documentId);
        m.mutable_redo()->set_edit_id(target);
        break;
    }
    return m;
  }

  // The id the server's Ack carries: the new edit's, or the undone/redone one.
  Expected<uint64_t> applyTo(Document& doc) const {
    switch (kind) {
      case Kind::kMove: {
        TESSERA_ASSIGN_OR_RETURN(EditId id, doc.moveBy(std::span(&vertex, 1), displacement));
        return id.value;
      }
      case Kind::kCrease: {
        TESSERA_ASSIGN_OR_RETURN(EditId id, doc.setEdgeSharpness(edge, sharpness));
        return id.value;
      }
      case Kind::kUndo:
        TESSERA_RETURN_IF_ERROR(doc.undo(EditId{target}));
        return target;
      case Kind::kRedo:
        TESSERA_RETURN_IF_ERROR(doc.redo(EditId{target}));
        return target;
    }
    return target;
  }
};

inline const char* kindName(StormCommand::Kind kind) {
  switch (kind) {
    case StormCommand::Kind::kMove:
      return "move";
    case StormCommand::Kind::kCrease:
      return "crease";
    case StormCommand::Kind::kUndo:
      return "undo";
    case StormCommand::Kind::kRedo:
      return "redo";
  }
  return "?";
}

// Editor `part` of `parts` touches only the elements whose index is `part`
// modulo `parts`. Two editors' in-flight moves of one vertex, recovered in
// either order, sum to offsets that differ in the last bit: no observation
// tells them apart and no later command prunes one, so every such cycle
// would double the candidate histories for good. (Likewise two creases of
// one edge in flight.) Editors still interact through shared
// neighbourhoods: a coarse move tilts the frames of finer vertices that
// other editors move.
inline uint64_t pickIndex(std::mt19937& rng, uint64_t count, int part, int parts) {
  const auto p = static_cast<uint64_t>(part), n = static_cast<uint64_t>(parts);
  return p + n * (rng() % ((count - p + n - 1) / n));
}

// A signed move of a cube control vertex of level 0, 1 or 2 by up to 0.01
// per axis in steps of 1e-3 (the core history tests' randomCubeMove). The
// components are computed in signed arithmetic: `rng() % 21` is unsigned,
// and subtracting an unsigned 10 from it wrapped negative offsets to about
// 1.8e16, which the server refused as out of its grid.
inline StormCommand randomSignedMove(std::mt19937& rng, const LevelCounts& counts, int part = 0,
                                     int parts = 1) {
  StormCommand c;
  c.kind = StormCommand::Kind::kMove;
  const int level = static_cast<int>(rng() % 3);
  c.vertex = VertexId(level, pickIndex(rng, counts.vertices(level), part, parts));
  auto component = [&] { return (static_cast<int>(rng() % 21) - 10) * 1e-3; };
  const double x = component(), y = component(), z = component();
  c.displacement = Vec3(x, y, z);
  return c;
}

// An edge of level 0, 1 or 2 made smooth, semi-sharp (with a fractional
// part, so that the blend between rules is exercised) or infinitely sharp.
inline StormCommand randomCrease(std::mt19937& rng, const LevelCounts& counts, int part = 0, int parts = 1) {
  static constexpr float kSharpness[] = {0.0f, 0.5f, 1.0f, 1.7f, 2.5f, 4.0f, kSharpnessInfinite};
  StormCommand c;
  c.kind = StormCommand::Kind::kCrease;
  const int level = static_cast<int>(rng() % 3);
  c.edge = EdgeId(level, pickIndex(rng, counts.edges(level), part, parts));
  c.sharpness = kSharpness[rng() % std::size(kSharpness)];
  return c;
}

// What a replayed document will show now and after any later storm
// command, as exact bytes:
//   - for every vertex, its active offsets in edit order, bit for bit;
//   - for every edge and vertex tag, the last active one (later edits win),
//     or none;
//   - the next edit id (the ids later Acks name count from it).
//
// Why this is enough: the evaluators add a vertex's offsets one by one in
// edit order and let the last active tag of an element win
// (document_evaluator.h, sparse_hierarchy.cc), so the points and rules
// depend only on these; later moves resolve from those points. And the
// storm settles every edit at the end of its cycle: an editor undoes and
// redoes only its own edits acknowledged in the running cycle, so when a
// cycle is checked no existing edit will ever change its active flag
// again. Ids of existing edits, inactive edits and tags overridden by a
// later active one therefore never matter again. Two histories with one key
// are indistinguishable forever, and keeping one of them loses nothing.
//
// So one key covers same-level moves of different vertices recovered in
// either order (they commute exactly), and in-flight creases, undos and
// redos that changed nothing for good (a crease repeating the edge's value,
// an undo of a crease a later one overrides), which no observation could
// tell apart. Two moves of one vertex in either order, whose sums may round
// differently, get two keys: the storm keeps editors off each other's
// vertices for that reason.
//
// Merging candidates can only make the check stricter: the test passes a
// cycle when some kept history matches, so dropping a history could at
// worst fail a good run, never pass a lost edit.
inline std::string settledStateKey(const Document& doc) {
  auto put = [](std::string& out, const auto& value) {
    char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    out.append(bytes, sizeof(value));
  };
  std::map<uint64_t, std::string> offsets;             // packed vertex -> its active offsets
  std::map<std::tuple<int, uint64_t>, float> lastTag;  // (0 edge / 1 vertex, packed id) -> sharpness
  for (const Edit& edit : doc.edits()) {
    if (!edit.active) continue;
    if (const auto* move = std::get_if<MoveEdit>(&edit.change)) {
      for (const VertexOffset& o : move->offsets) {
        for (int k = 0; k < 3; ++k)
          put(offsets[o.vertex.packed()], std::bit_cast<uint64_t>(o.localOffset[k]));
      }
    } else if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
      lastTag[{0, e->edge.packed()}] = e->sharpness;
    } else {
      const auto& v = std::get<VertexSharpnessEdit>(edit.change);
      lastTag[{1, v.vertex.packed()}] = v.sharpness;
    }
  }
  std::string key;
  put(key, doc.nextEditId());
  for (const auto& [vertex, bits] : offsets) {
    put(key, vertex);
    put(key, bits.size());
    key += bits;
  }
  for (const auto& [element, sharpness] : lastTag) {
    put(key, std::get<0>(element));
    put(key, std::get<1>(element));
    put(key, std::bit_cast<uint32_t>(sharpness));
  }
  return key;
}

}  // namespace tessera::testing
