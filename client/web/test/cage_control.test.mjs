// The cage toggle's asking (src/ui/cage_control.js) with a stand-in session
// and layer: nothing is asked while off or before the document is open; a
// level is asked once and kept; a refusal is shown and not asked again; a
// request lost with the connection is asked again.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { CageControl } from '../src/ui/cage_control.js';
import { RejectError } from '../src/session/connection.js';

// A session whose cage(level) answers with `answer(level)` (a Cage's fields,
// or a thrown error) when the test says so.
function fakeSession(answer) {
  const session = { opened: false, asked: [], waiting: [] };
  session.cage = (level) => {
    session.asked.push(level);
    return new Promise((resolve, reject) => session.waiting.push(() => {
      try { resolve(answer(level)); } catch (error) { reject(error); }
    }));
  };
  session.answerAll = async () => {
    for (const go of session.waiting.splice(0)) go();
    await new Promise((r) => setTimeout(r, 0));
  };
  return session;
}

const quad = (level) => ({ level, face_sizes: [4], vertices: [0, 1, 2, 3] });

function setUp(session) {
  const layer = { cage: null, segments: 0, tooLarge: false, setCage(c) { this.cage = c; } };
  const errors = [];
  let level = 0;
  const control = new CageControl({ layer, session: () => session, level: () => level, onError: (e) => errors.push(e) });
  return { control, layer, errors, setLevel: (l) => { level = l; control.sync(); } };
}

test('asked once the toggle is on and the document open, once per level, and handed to the layer', async () => {
  const session = fakeSession(quad);
  const { control, layer, setLevel } = setUp(session);
  control.sync();
  assert.deepEqual(session.asked, [], 'off: nothing asked');
  control.setOn(true);
  assert.equal(control.facts().status, 'waiting');
  assert.deepEqual(session.asked, [], 'the document is not open yet');
  session.opened = true;
  control.sync();
  control.sync();
  assert.deepEqual(session.asked, [0], 'asked once, however often synced');
  assert.equal(control.facts().status, 'asking');
  await session.answerAll();
  assert.equal(control.facts().status, 'shown');
  assert.equal(layer.cage.edges.length, 4);
  assert.deepEqual([control.facts().faces, control.facts().edges, control.facts().faceSizes], [1, 4, { 4: 1 }]);
  setLevel(1);
  assert.equal(layer.cage, null, 'nothing of level 0 drawn at level 1');
  await session.answerAll();
  assert.equal(layer.cage.level, 1);
  setLevel(0);
  assert.equal(layer.cage.level, 0, 'level 0 kept');
  control.toggle();
  assert.equal(layer.cage, null);
  assert.equal(control.facts().status, 'off');
  control.toggle();
  assert.deepEqual(session.asked, [0, 1]);
  assert.equal(control.facts().requests, 2);
});

test('a refused level is shown and not asked again; a lost request is', async () => {
  let lose = true;
  const session = fakeSession((level) => {
    if (level === 5) throw new RejectError(1, 'REJECT_REASON_INVALID_ARGUMENT', 'level 5 is outside 0..2');
    if (lose) { lose = false; throw new Error('the connection was lost before the answer came'); }
    return quad(level);
  });
  session.opened = true;
  const { control, errors, setLevel } = setUp(session);
  setLevel(5);
  control.setOn(true);
  await session.answerAll();
  assert.equal(control.facts().status, 'refused');
  assert.deepEqual(errors, ['control cage of level 5: REJECT_REASON_INVALID_ARGUMENT: level 5 is outside 0..2']);
  control.sync();
  assert.deepEqual(session.asked, [5], 'not asked again');

  setLevel(2);
  await session.answerAll();
  assert.equal(control.facts().status, 'waiting', 'lost: waits for the next sync');
  assert.equal(errors.length, 1, 'a lost connection is the connection\'s to report');
  control.sync();
  await session.answerAll();
  assert.equal(control.facts().status, 'shown');
  assert.deepEqual(session.asked, [5, 2, 2]);
});

test('another session forgets what the last one was answered', async () => {
  let session = fakeSession(quad);
  session.opened = true;
  const layer = { cage: null, segments: 0, tooLarge: false, setCage(c) { this.cage = c; } };
  const control = new CageControl({ layer, session: () => session, level: () => 0, onError: () => {} });
  control.setOn(true);
  await session.answerAll();
  assert.equal(control.facts().status, 'shown');
  session = fakeSession(quad);
  session.opened = true;
  control.sync();
  assert.deepEqual(session.asked, [0]);
  assert.equal(layer.cage, null);
});
