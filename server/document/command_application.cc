#include "server/document/command_application.h"

#include <algorithm>
#include <string>

#include "protocol/commands.h"
#include "protocol/morph_key.h"
#include "server/base/log.h"
#include "server/document/morph_key_command.h"

namespace tessera::server {

namespace {

// One command that is not a batch.
Status applyOne(KeyedDocument& keyed, store::DocumentId id, const wire::ClientMessage& message,
                uint64_t& editId, JournalEntry& entry) {
  if (message.has_add_morph_key()) return applyAddMorphKey(keyed, id, message.add_morph_key(), entry);
  entry.key = morphKeyOf(message);
  TESSERA_ASSIGN_OR_RETURN(Document * edited, keyed.editKey(entry.key));
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

// Adds what the last command changed on `key` to `applied`.
void collectLimits(const KeyedDocument& keyed, uint32_t key, AppliedChange& applied) {
  const auto& limits = keyed.key(key).lastUpdate().limits;
  auto& into = key == 0 ? applied.limits : applied.key1Limits;
  into.insert(into.end(), limits.begin(), limits.end());
}

Status applyBatch(KeyedDocument& keyed, store::DocumentId id, const wire::EditBatch& batch,
                  AppliedChange& applied) {
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
    Status status =
        command.command_case() == wire::EditCommand::COMMAND_NOT_SET ? invalidArgument("no command")
        : named != 0 && named != id.value ? invalidArgument("names document " + std::to_string(named) +
                                                            ", the batch is for " + std::to_string(id.value))
                                          : applyOne(keyed, id, one, editId, part);
    if (!status.isOk()) {
      // All or nothing: what the batch applied goes back, newest first.
      Status back = retractCommand(keyed, applied.entry);
      if (!back.isOk())
        logEvent(LogLevel::kError, "retract_failed", {{"doc", id.value}, {"error", back.message()}});
      applied.failedIndex = static_cast<uint32_t>(i + 1);
      return Status(status.code(), "edit batch, command " + std::to_string(i + 1) + " of " +
                                       std::to_string(count) + ": " + status.message() +
                                       " (nothing of the batch was applied)");
    }
    collectLimits(keyed, part.key, applied);
    applied.editIds.push_back(editId);
    applied.entry.batch.push_back(std::move(part));
  }
  for (auto* limits : {&applied.limits, &applied.key1Limits}) {
    std::sort(limits->begin(), limits->end());
    limits->erase(std::unique(limits->begin(), limits->end()), limits->end());
  }
  return Status::ok();
}

}  // namespace

Status applyCommand(KeyedDocument& keyed, store::DocumentId id, const wire::ClientMessage& message,
                    AppliedChange& applied) {
  if (message.has_edit_batch()) return applyBatch(keyed, id, message.edit_batch(), applied);
  uint64_t editId = 0;
  TESSERA_RETURN_IF_ERROR(applyOne(keyed, id, message, editId, applied.entry));
  applied.editIds.push_back(editId);
  if (applied.entry.kind == JournalEntry::Kind::kAddKey) {
    // The new key's every base limit, for the host's grid check.
    const int n = keyed.key(1).baseTopology().numVertices;
    for (int v = 0; v < n; ++v) applied.key1Limits.push_back(VertexId(0, static_cast<uint64_t>(v)));
  } else {
    collectLimits(keyed, applied.entry.key, applied);
  }
  return Status::ok();
}

// The views never saw the command (they update at the next flush), so only
// the document goes back; its limits are restored bit for bit.
Status retractCommand(KeyedDocument& keyed, const JournalEntry& entry) {
  if (entry.kind == JournalEntry::Kind::kAddKey) {
    keyed.removeLastKey();
    return Status::ok();
  }
  Document* doc = nullptr;
  if (entry.kind != JournalEntry::Kind::kBatch) {
    TESSERA_ASSIGN_OR_RETURN(doc, keyed.editKey(entry.key));
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
        TESSERA_RETURN_IF_ERROR(retractCommand(keyed, *part));
      return Status::ok();
  }
  return Status::ok();
}

}  // namespace tessera::server
