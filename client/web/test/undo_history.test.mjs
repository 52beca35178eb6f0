// The undo rule of docs/VIEWER.md, as client/view/undo_history.h has it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { UndoHistory } from '../src/session/undo_history.js';

test('a drag is one step: undo newest first, redo oldest first', () => {
  const h = new UndoHistory();
  const drag = h.open();
  for (let i = 0; i < 3; ++i) h.sent(drag);
  assert.throws(() => h.undo(), /still being made/);
  h.close(drag);
  assert.throws(() => h.undo(), /3 edits of the last step await/);
  assert.equal(h.awaitingAnswers(), 3);
  h.acked(drag, 10);
  h.acked(drag, 11);
  h.dropped(drag); // rejected: not part of the step
  assert.equal(h.awaitingAnswers(), 0);
  assert.deepEqual(h.undo(), [11n, 10n]);
  assert.throws(() => h.undo(), /nothing/);
  assert.deepEqual(h.redo(), [10n, 11n]);
  assert.deepEqual(h.undo(), [11n, 10n]);
});

test('a click without a move is no step, and a new step drops the redo list', () => {
  const h = new UndoHistory();
  const first = h.open();
  h.sent(first);
  h.close(first);
  h.acked(first, 1);
  const click = h.open();
  h.close(click);
  assert.deepEqual(h.undo(), [1n]); // the empty click step left no trace
  const next = h.open();
  h.sent(next);
  h.close(next);
  h.acked(next, 2);
  assert.throws(() => h.redo(), /nothing/);
});

test('the pacer keeps the rate, and jobs it clears away leave their step', async () => {
  const { Pacer } = await import('../src/session/pacer.js');
  let now = 0;
  const pacer = new Pacer(10, 2, () => now);
  const ran = [];
  for (let i = 0; i < 4; ++i) pacer.run(() => ran.push(i));
  assert.deepEqual(ran, [0, 1], 'a burst of two');
  now = 100;
  pacer.drain();
  assert.deepEqual(ran, [0, 1, 2], 'one more after 0.1 s at 10 a second');
  const h = new UndoHistory();
  const step = h.open();
  h.sent(step);
  h.close(step);
  const job = () => ran.push('edit');
  job.drop = () => h.dropped(step);
  pacer.run(job);
  pacer.clear();
  assert.throws(() => h.undo(), /nothing/, 'the cleared edit left no step');
  assert.equal(ran.includes('edit'), false);
});
