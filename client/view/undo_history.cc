#include "client/view/undo_history.h"

#include <algorithm>
#include <string>

namespace tessera::view {

UndoHistory::StepId UndoHistory::open() {
  done_.push_back({.id = next_, .edits = {}, .pending = 0, .open = true});
  return next_++;
}

UndoHistory::Step* UndoHistory::find(StepId step) {
  for (auto it = done_.rbegin(); it != done_.rend(); ++it)
    if (it->id == step) return &*it;
  return nullptr;
}

// A closed step left without any edit is no step at all.
void UndoHistory::dropIfEmpty(StepId step) {
  Step* s = find(step);
  if (s && !s->open && s->pending == 0 && s->edits.empty()) {
    done_.erase(done_.begin() + (s - done_.data()));
  }
}

void UndoHistory::close(StepId step) {
  if (Step* s = find(step)) s->open = false;
  dropIfEmpty(step);
}

void UndoHistory::sent(StepId step) {
  if (Step* s = find(step)) ++s->pending;
}

void UndoHistory::acked(StepId step, uint64_t editId) {
  Step* s = find(step);
  if (!s) return;
  if (s->edits.empty()) undone_.clear();
  s->edits.push_back(editId);
  s->pending = std::max(0, s->pending - 1);
}

void UndoHistory::dropped(StepId step) {
  if (Step* s = find(step)) s->pending = std::max(0, s->pending - 1);
  dropIfEmpty(step);
}

namespace {

template <typename Step>
Status ready(const std::vector<Step>& steps, const char* what) {
  if (steps.empty()) return invalidArgument(std::string("nothing of this viewer's to ") + what);
  const Step& s = steps.back();
  if (s.open)
    return invalidArgument(std::string("cannot ") + what + " while the last step is still being made");
  if (s.pending > 0) {
    return invalidArgument(std::string("cannot ") + what + " yet: " + std::to_string(s.pending) +
                           " edits of the last step await their answer");
  }
  return Status::ok();
}

}  // namespace

Expected<std::vector<uint64_t>> UndoHistory::undo() {
  TESSERA_RETURN_IF_ERROR(ready(done_, "undo"));
  std::vector<uint64_t> ids(done_.back().edits.rbegin(), done_.back().edits.rend());
  undone_.push_back(std::move(done_.back()));
  done_.pop_back();
  return ids;
}

Expected<std::vector<uint64_t>> UndoHistory::redo() {
  TESSERA_RETURN_IF_ERROR(ready(undone_, "redo"));
  std::vector<uint64_t> ids = undone_.back().edits;
  done_.push_back(std::move(undone_.back()));
  undone_.pop_back();
  return ids;
}

}  // namespace tessera::view
