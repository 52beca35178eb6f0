// This viewer's own edits, grouped into the steps the user undoes and redoes
// (docs/VIEWER.md "Undo and redo", client/view/undo_history.h).
//
// A drag is one step from press to release, however many MoveVertex edits
// it sent; every other edit is a step of its own. A step holds the edit ids
// of its Acks, oldest first. Undo takes back the newest step, sending Undo
// for its edits newest first; redo replays the newest undone step, oldest
// first. A step can be undone once it is closed and every edit of it is
// answered. Rejected edits, and edits lost with the connection, leave their
// step; a closed step left empty is no step. The first Ack of a new step
// drops the steps that could be redone.
export class UndoHistory {
  constructor() {
    this.done = []; // oldest first
    this.undone = [];
    this.next = 1;
  }

  open() {
    this.done.push({ id: this.next, edits: [], pending: 0, open: true });
    return this.next++;
  }

  find(step) {
    for (let i = this.done.length - 1; i >= 0; --i) if (this.done[i].id === step) return this.done[i];
    return null;
  }

  dropIfEmpty(step) {
    const s = this.find(step);
    if (s && !s.open && s.pending === 0 && s.edits.length === 0) this.done.splice(this.done.indexOf(s), 1);
  }

  close(step) {
    const s = this.find(step);
    if (s) s.open = false;
    this.dropIfEmpty(step);
  }

  sent(step) {
    const s = this.find(step);
    if (s) ++s.pending;
  }

  acked(step, editId) {
    const s = this.find(step);
    if (!s) return;
    if (s.edits.length === 0) this.undone = [];
    s.edits.push(BigInt(editId));
    s.pending = Math.max(0, s.pending - 1);
  }

  // Edits sent and not answered yet, in every step (undo waits for them).
  awaitingAnswers() {
    return this.done.reduce((n, s) => n + s.pending, 0);
  }

  dropped(step) {
    const s = this.find(step);
    if (s) s.pending = Math.max(0, s.pending - 1);
    this.dropIfEmpty(step);
  }

  // The edit ids to undo, newest first; throws an Error saying why when
  // nothing can be undone now.
  undo() {
    ready(this.done, 'undo');
    const step = this.done.pop();
    this.undone.push(step);
    return step.edits.slice().reverse();
  }

  // The edit ids to redo, oldest first.
  redo() {
    ready(this.undone, 'redo');
    const step = this.undone.pop();
    this.done.push(step);
    return step.edits.slice();
  }
}

function ready(steps, what) {
  if (steps.length === 0) throw new Error(`nothing of this viewer's to ${what}`);
  const s = steps[steps.length - 1];
  if (s.open) throw new Error(`cannot ${what} while the last step is still being made`);
  if (s.pending > 0) throw new Error(`cannot ${what} yet: ${s.pending} edits of the last step await their answer`);
}
