// UndoHistory: tessera-view's own edits, grouped into the steps the user
// undoes and redoes (docs/VIEWER.md, "Undo and redo").
//
// The rule: every edit the viewer sends belongs to one step. A drag is one
// step, from the press to the release, however many MoveVertex edits it
// sends; every other edit (K, E) is a step of its own. A step holds the edit
// ids of its Acks, oldest first (one connection's Acks of one document come
// in version order). Undo takes back the newest step, sending Undo for its
// edits newest first; redo replays the newest undone step, oldest first. A
// step can be undone once it is closed and every edit of it is answered;
// before that, undo and redo refuse and say why. Rejected edits, and edits
// whose answer was lost with the connection, are left out of their step. The
// first Ack of a new step drops the steps that could be redone.
//
// Not thread-safe: the Connection holds its mutex around every call.
#pragma once

#include <cstdint>
#include <vector>

#include "core/util/status.h"

namespace tessera::view {

class UndoHistory {
 public:
  using StepId = uint64_t;

  StepId open();            // a new step, newest in the history
  void close(StepId step);  // no more edits will join it
  void sent(StepId step);   // one more edit of the step awaits its answer
  void acked(StepId step, uint64_t editId);
  void dropped(StepId step);  // rejected, or lost with the connection

  // The edit ids to undo, newest first, and the step moves to the redo list;
  // an error saying why when nothing can be undone now.
  Expected<std::vector<uint64_t>> undo();
  // The edit ids to redo, oldest first.
  Expected<std::vector<uint64_t>> redo();

  size_t undoable() const { return done_.size(); }
  size_t redoable() const { return undone_.size(); }

 private:
  struct Step {
    StepId id = 0;
    std::vector<uint64_t> edits;
    int pending = 0;
    bool open = true;
  };
  Step* find(StepId step);
  void dropIfEmpty(StepId step);

  std::vector<Step> done_, undone_;  // oldest first
  StepId next_ = 1;
};

// A morph document numbers edit ids per key, and an Undo or Redo names the
// key of its edit (docs/PROTOCOL.md 7.2, "Undo, Redo"). The history holds
// the edits of key 1 with kKeyOneBit set (edit ids stay far below it), so
// that each id it gives back names its key.
inline constexpr uint64_t kKeyOneBit = uint64_t{1} << 63;

struct KeyedEdit {
  uint64_t editId = 0;
  uint32_t key = 0;  // 0 or 1
};

// The id the history holds for edit `editId` of `key` (any key but 1 is key 0).
inline uint64_t keyedEditId(uint64_t editId, uint32_t key) {
  return editId | (key == 1 ? kKeyOneBit : 0);
}
inline KeyedEdit splitKeyedEditId(uint64_t keyed) {
  return {.editId = keyed & ~kKeyOneBit, .key = (keyed & kKeyOneBit) != 0 ? 1u : 0u};
}

}  // namespace tessera::view
