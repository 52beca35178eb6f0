#include "core/document/edit_codec.h"

namespace tessera {

namespace {

enum class EditKind : uint8_t { kMove = 1, kEdgeSharpness = 2, kVertexSharpness = 3 };

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
  if (active > 1) return parseError(r.source() + ": " + edit.id.toString() + ": bad state " + std::to_string(active));
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
  }
  return parseError(r.source() + ": " + edit.id.toString() + ": unknown edit kind " + std::to_string(kind));
}

}  // namespace tessera
