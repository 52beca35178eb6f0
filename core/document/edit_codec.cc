#include "core/document/edit_codec.h"

namespace tessera {

namespace {

// Kind 4 (interpolation) is new in document format 2 and journal entries
// written since; older readers refuse it as an unknown kind.
enum class EditKind : uint8_t { kMove = 1, kEdgeSharpness = 2, kVertexSharpness = 3, kInterpolation = 4 };

}  // namespace

void writeEdit(const Edit& edit, ByteWriter& w) {
  w.put<uint64_t>(edit.id.value);
  w.put<uint8_t>(edit.active ? 1 : 0);
  if (const auto* move = std::get_if<MoveEdit>(&edit.change)) {
    w.put<uint8_t>(static_cast<uint8_t>(EditKind::kMove));
    w.put<uint32_t>(static_cast<uint32_t>(move->offsets.size()));
    for (const auto& o : move->offsets) {
      w.put<uint64_t>(o.vertex.packed());
      for (int k = 0; k < 3; ++k) w.put<double>(o.localOffset[k]);
    }
  } else if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
    w.put<uint8_t>(static_cast<uint8_t>(EditKind::kEdgeSharpness));
    w.put<uint64_t>(e->edge.packed());
    w.put<float>(e->sharpness);
  } else if (const auto* t = std::get_if<InterpolationEdit>(&edit.change)) {
    w.put<uint8_t>(static_cast<uint8_t>(EditKind::kInterpolation));
    w.put<uint64_t>(t->vertex.packed());
    w.put<uint8_t>(t->interpolating ? 1 : 0);
    w.put<double>(t->tension);
    for (int k = 0; k < 3; ++k) w.put<double>(t->tangent[k]);
  } else {
    const auto& v = std::get<VertexSharpnessEdit>(edit.change);
    w.put<uint8_t>(static_cast<uint8_t>(EditKind::kVertexSharpness));
    w.put<uint64_t>(v.vertex.packed());
    w.put<float>(v.sharpness);
  }
}

Expected<Edit> readEdit(ByteReader& r) {
  Edit edit;
  uint8_t active = 0, kind = 0;
  TESSERA_RETURN_IF_ERROR(r.get(edit.id.value, "an edit id"));
  TESSERA_RETURN_IF_ERROR(r.get(active, "an edit state"));
  TESSERA_RETURN_IF_ERROR(r.get(kind, "an edit kind"));
  if (active > 1)
    return parseError(r.source() + ": " + edit.id.toString() + ": bad state " + std::to_string(active));
  edit.active = active == 1;
  uint64_t packed = 0;
  switch (static_cast<EditKind>(kind)) {
    case EditKind::kMove: {
      MoveEdit move;
      uint32_t count = 0;
      TESSERA_RETURN_IF_ERROR(r.getCount(count, 8 + 3 * 8, "moved vertex count"));
      for (uint32_t i = 0; i < count; ++i) {
        VertexOffset o;
        TESSERA_RETURN_IF_ERROR(r.get(packed, "a vertex id"));
        o.vertex = VertexId::fromPacked(packed);
        for (int k = 0; k < 3; ++k) TESSERA_RETURN_IF_ERROR(r.get(o.localOffset[k], "an offset"));
        move.offsets.push_back(o);
      }
      edit.change = std::move(move);
      return edit;
    }
    case EditKind::kEdgeSharpness: {
      EdgeSharpnessEdit e;
      TESSERA_RETURN_IF_ERROR(r.get(packed, "an edge id"));
      e.edge = EdgeId::fromPacked(packed);
      TESSERA_RETURN_IF_ERROR(r.get(e.sharpness, "a sharpness"));
      edit.change = e;
      return edit;
    }
    case EditKind::kVertexSharpness: {
      VertexSharpnessEdit v;
      TESSERA_RETURN_IF_ERROR(r.get(packed, "a vertex id"));
      v.vertex = VertexId::fromPacked(packed);
      TESSERA_RETURN_IF_ERROR(r.get(v.sharpness, "a sharpness"));
      edit.change = v;
      return edit;
    }
    case EditKind::kInterpolation: {
      InterpolationEdit t;
      uint8_t on = 0;
      TESSERA_RETURN_IF_ERROR(r.get(packed, "a vertex id"));
      t.vertex = VertexId::fromPacked(packed);
      TESSERA_RETURN_IF_ERROR(r.get(on, "an interpolation state"));
      if (on > 1) {
        return parseError(r.source() + ": " + edit.id.toString() + ": bad interpolation state " +
                          std::to_string(on));
      }
      t.interpolating = on == 1;
      TESSERA_RETURN_IF_ERROR(r.get(t.tension, "a tension"));
      for (int k = 0; k < 3; ++k) TESSERA_RETURN_IF_ERROR(r.get(t.tangent[k], "a tangent"));
      edit.change = t;
      return edit;
    }
  }
  return parseError(r.source() + ": " + edit.id.toString() + ": unknown edit kind " + std::to_string(kind));
}

}  // namespace tessera
