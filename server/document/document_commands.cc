// The commands of a document host turned into document changes
// (docs/PROTOCOL.md §5, and §14 for the keys): one edit, undo or redo, an
// EditBatch all or nothing, a second morph key (document_morph.cc), and
// their retraction when the server refuses a command after applying it.
#include <algorithm>

#include "protocol/commands.h"
#include "protocol/morph_key.h"
#include "server/base/log.h"
#include "server/document/document_host.h"

namespace tessera::server {

Status DocumentHost::apply(const wire::ClientMessage& message, uint64_t& editId, JournalEntry& entry) {
  if (message.has_add_morph_key()) return addMorphKey(message.add_morph_key(), entry);
  entry.key = morphKeyOf(message);
  TESSERA_ASSIGN_OR_RETURN(Document * edited, doc_.editKey(entry.key));
  Document& doc = *edited;
  auto addedEdit = [&](Expected<EditId> id) -> Status {
    TESSERA_RETURN_IF_ERROR(id.status());
    editId = id->value;
    entry.kind = JournalEntry::Kind::kEdit;
    entry.edit = doc.edits().back();
    return Status::ok();
  };
  switch (message.command_case()) {
    case wire::ClientMessage::kMoveVertex: {
      const auto& m = message.move_vertex();
      std::vector<VertexId> vertices;
      for (uint64_t packed : m.vertex_ids()) vertices.push_back(VertexId::fromPacked(packed));
      const Vec3 target(m.target().x(), m.target().y(), m.target().z());
      if (m.mode() == wire::MOVE_MODE_OFFSET) return addedEdit(doc.moveBy(vertices, target));
      if (m.mode() != wire::MOVE_MODE_DIRECT_MANIPULATION) return invalidArgument("move: mode is not set");
      return addedEdit(doc.moveToLimit(vertices, target));
    }
    case wire::ClientMessage::kSetEdgeSharpness: {
      const auto& m = message.set_edge_sharpness();
      EdgeId edge = EdgeId::fromPacked(m.edge_id());
      if (m.end_vertex_ids_size() > 0) {  // the edge named by its ends instead
        if (m.end_vertex_ids_size() != 2 || m.edge_id() != kEdgeIdNamedByEnds) {
          return invalidArgument(
              "edge sharpness: end_vertex_ids needs exactly two ids and edge_id all ones, got " +
              std::to_string(m.end_vertex_ids_size()) + " ids and edge_id " + std::to_string(m.edge_id()));
        }
        TESSERA_ASSIGN_OR_RETURN(edge, doc.edgeBetween(VertexId::fromPacked(m.end_vertex_ids(0)),
                                                       VertexId::fromPacked(m.end_vertex_ids(1))));
      }
      return addedEdit(doc.setEdgeSharpness(edge, m.sharpness()));
    }
    case wire::ClientMessage::kSetVertexType: {
      const auto& m = message.set_vertex_type();
      float sharpness = 0.0f;
      if (m.value_case() == wire::SetVertexType::kSharpness) {
        sharpness = m.sharpness();
      } else if (m.type() == wire::VERTEX_TYPE_CUSP || m.type() == wire::VERTEX_TYPE_CORNER) {
        sharpness = kSharpnessInfinite;
      } else if (m.type() != wire::VERTEX_TYPE_SMOOTH) {
        return invalidArgument("vertex type: no type or sharpness given");
      }
      return addedEdit(doc.setVertexSharpness(VertexId::fromPacked(m.vertex_id()), sharpness));
    }
    case wire::ClientMessage::kSetInterpolation: {
      const auto& m = message.set_interpolation();
      const double tension = m.tension() == 0.0 ? 1.0 : m.tension();
      const Vec3 tangent(m.tangent().x(), m.tangent().y(), m.tangent().z());
      return addedEdit(
          doc.setInterpolation(VertexId::fromPacked(m.vertex_id()), m.interpolating(), tension, tangent));
    }
    case wire::ClientMessage::kUndo:
    case wire::ClientMessage::kRedo: {
      const bool undo = message.command_case() == wire::ClientMessage::kUndo;
      const EditId target{undo ? message.undo().edit_id() : message.redo().edit_id()};
      TESSERA_RETURN_IF_ERROR(undo ? doc.undo(target) : doc.redo(target));
      editId = target.value;
      entry.kind = undo ? JournalEntry::Kind::kUndo : JournalEntry::Kind::kRedo;
      entry.target = target;
      return Status::ok();
    }
    default:
      return invalidArgument("not an edit command");
  }
}

Status DocumentHost::applyBatch(const wire::EditBatch& batch, Applied& applied, uint32_t& failedIndex) {
  const int count = batch.commands_size();
  if (count == 0) return invalidArgument("edit batch: no commands");
  applied.entry.kind = JournalEntry::Kind::kBatch;
  for (int i = 0; i < count; ++i) {
    const wire::EditCommand& command = batch.commands(i);
    wire::ClientMessage one;
    unwrapEditCommand(command, one);
    const uint64_t named = documentOf(one);
    JournalEntry part;
    uint64_t editId = 0;
    Status status = command.command_case() == wire::EditCommand::COMMAND_NOT_SET
                        ? invalidArgument("no command")
                    : named != 0 && named != id_.value
                        ? invalidArgument("names document " + std::to_string(named) + ", the batch is for " +
                                          std::to_string(id_.value))
                        : apply(one, editId, part);
    if (!status.isOk()) {
      // All or nothing: what the batch applied goes back, newest first.
      Status back = retract(applied.entry);
      if (!back.isOk())
        logEvent(LogLevel::kError, "retract_failed", {{"doc", id_.value}, {"error", back.message()}});
      failedIndex = static_cast<uint32_t>(i + 1);
      return Status(status.code(), "edit batch, command " + std::to_string(i + 1) + " of " +
                                       std::to_string(count) + ": " + status.message() +
                                       " (nothing of the batch was applied)");
    }
    collectLimits(part.key, applied);
    applied.editIds.push_back(editId);
    applied.entry.batch.push_back(std::move(part));
  }
  for (auto* limits : {&applied.limits, &applied.key1Limits}) {
    std::sort(limits->begin(), limits->end());
    limits->erase(std::unique(limits->begin(), limits->end()), limits->end());
  }
  return Status::ok();
}

void DocumentHost::collectLimits(uint32_t key, Applied& applied) const {
  const auto& limits = doc_.key(key).lastUpdate().limits;
  auto& into = key == 0 ? applied.limits : applied.key1Limits;
  into.insert(into.end(), limits.begin(), limits.end());
}

// The views never saw the command (they update at the next flush), so only
// the document goes back; its limits are restored bit for bit.
Status DocumentHost::retract(const JournalEntry& entry) {
  if (entry.kind == JournalEntry::Kind::kAddKey) {
    doc_.removeLastKey();
    return Status::ok();
  }
  Document* doc = nullptr;
  if (entry.kind != JournalEntry::Kind::kBatch) {
    TESSERA_ASSIGN_OR_RETURN(doc, doc_.editKey(entry.key));
  }
  switch (entry.kind) {
    case JournalEntry::Kind::kAddKey:
      return Status::ok();
    case JournalEntry::Kind::kEdit:
      return doc->retractLast();
    case JournalEntry::Kind::kUndo:
      return doc->reinstate(entry.target);
    case JournalEntry::Kind::kRedo:
      return doc->undo(entry.target);
    case JournalEntry::Kind::kBatch:
      for (auto part = entry.batch.rbegin(); part != entry.batch.rend(); ++part)
        TESSERA_RETURN_IF_ERROR(retract(*part));
      return Status::ok();
  }
  return Status::ok();
}

}  // namespace tessera::server
