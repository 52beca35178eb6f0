// Snapshots and deltas whose regions decode elsewhere (src/session/
// ordered_updates.js; docs/WEB_VIEWER.md "Decoding in a worker"), through a
// DocumentSession as the page wires it, with stand-in decode workers: the
// answers come back in any order and the view still moves version by
// version in the order the messages arrived; a payload that does not decode
// is a gap with the synchronous decoder's message and a new subscription;
// what waits behind a gap is not waited for; a new connection drops what
// the old one left queued.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import Long from 'long';
import { DecodePool } from '../src/codec/decode_pool.js';
import { decodeRegion } from '../src/codec/region_decoder.js';
import { DocumentSession } from '../src/session/document_session.js';
import { DocumentView, regionPayloads } from '../src/session/document_view.js';
import { OrderedUpdates } from '../src/session/ordered_updates.js';
import { dracoDecoder, dracoEncoder } from './support/draco_node.mjs';
import { FakeDecodeWorker } from './support/fake_decode_worker.mjs';
import { testRegion } from './support/test_regions.mjs';

const L = (n) => Long.fromValue(n, true);
const snapshot = (version, regions) => ({ snapshot: { document_id: L(1), version: L(version), regions, remaining_parts: 0, surface_hash: L(0), resync: false } });
const delta = (from, to, regions) => ({ delta: { document_id: L(1), from_version: L(from), to_version: L(to), regions, removed_region_ids: [], surface_hash: L(0), author_session_id: L(5), edit_id: L(3) } });
const region = (enc, id, version) => ({ region_id: L(id), draco: testRegion(enc, BigInt(id), BigInt(version)) });

// A session over a connection that answers every call with an Ack, and
// two stand-in workers, as the page has a DecodePool.
async function sessionWithWorkers(workerCount = 2) {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const workers = Array.from({ length: workerCount }, () => new FakeDecodeWorker(draco));
  let next = 0;
  const pool = new DecodePool({ createWorker: () => workers[next++], size: workerCount });
  workers.forEach((w) => w.start());
  const calls = [], changes = [], errors = [];
  const connection = { call: async (m) => { calls.push(m); return { message: { ack: { version: L(0) } } }; } };
  const session = new DocumentSession({
    connection, documentId: 1n, profile: { baseLevel: 1, maxLevel: 1, angle: 15 }, view: null,
    decode: (bytes) => pool.decode(bytes),
    onView: (change) => changes.push(`${change.kind} v${session.view.version}`),
    onError: (text) => errors.push(text),
  });
  return { draco, enc, workers, pool, session, calls, changes, errors };
}

const settle = () => new Promise((resolve) => setImmediate(resolve));

test('answers that come back newest first are applied in the order the messages came', async () => {
  const { enc, workers, session, changes, errors } = await sessionWithWorkers();
  session.message('snapshot', snapshot(1, [region(enc, 10, 1), region(enc, 11, 1)]));
  session.message('delta', delta(1, 2, [region(enc, 10, 2)]));
  session.message('delta', delta(2, 3, [region(enc, 10, 3), region(enc, 11, 3)]));
  assert.equal(session.updates.pending, 3, 'nothing applied before its regions are decoded');
  await settle();
  assert.deepEqual(workers.map((w) => w.requests.length), [3, 2], 'the requests share the workers');
  // The last message's regions first, then the others, worker by worker.
  workers[1].answerAllBackwards();
  await settle();
  assert.deepEqual(changes, [], 'a later message waits for the earlier');
  workers[0].answerAllBackwards();
  await settle();
  assert.deepEqual(changes, ['snapshot v1', 'delta v2', 'delta v3']);
  assert.deepEqual(errors, []);
  assert.equal(session.view.regions.get(10n).header.documentVersion, 3n);
  assert.equal(session.view.regions.get(11n).header.documentVersion, 3n);
  assert.equal(session.lastHash.matches, true);
  assert.equal(session.updates.pending, 0);
});

test('a payload that fails its checksum is a gap with the synchronous decoder\'s message; the session subscribes again', async () => {
  const { draco, enc, workers, session, calls, changes, errors } = await sessionWithWorkers();
  const bad = region(enc, 10, 2);
  bad.draco[bad.draco.length - 9] ^= 0x40;
  let expected;
  assert.throws(() => decodeRegion(draco, bad.draco), (error) => { expected = error.message; return true; });
  session.message('snapshot', snapshot(1, [region(enc, 10, 1)]));
  session.message('delta', delta(1, 2, [bad]));
  session.message('delta', delta(2, 3, [region(enc, 10, 3)])); // behind the gap: ignored
  session.message('snapshot', snapshot(3, [region(enc, 10, 3)])); // the new subscription's
  await settle();
  for (const w of workers) w.answerAllBackwards();
  await settle();
  assert.deepEqual(errors, [`${expected}; subscribing again`]);
  assert.equal(calls.filter((c) => c.subscribe).length, 1, 'one Subscribe');
  assert.equal(session.view.gaps, 1);
  assert.deepEqual(changes, ['snapshot v1', 'snapshot v3'], 'the delta behind the gap is ignored, the snapshot applies');
  assert.equal(session.view.ready, true);
});

test('a worker that stops is a gap too, never a hang', async () => {
  const { enc, workers, session, changes, errors } = await sessionWithWorkers(1);
  session.message('snapshot', snapshot(1, [region(enc, 10, 1)]));
  workers[0].crash('out of memory');
  await settle();
  assert.equal(session.updates.pending, 0);
  assert.deepEqual(changes, []);
  assert.deepEqual(errors, ['the decode worker stopped: out of memory; subscribing again']);
});

// OrderedUpdates alone, with decodes the test settles by hand.
function deferredDecoder() {
  const waiting = [];
  const decode = (bytes) => new Promise((resolve, reject) => waiting.push({ bytes, resolve, reject }));
  return { decode, waiting };
}
const fakeRegion = (n) => ({ header: { idsInline: true, hasIds: true, layoutVersion: 1n }, indices: new Uint32Array(3), positions: new Float32Array(9), normals: new Float32Array(9), idHi: new Uint32Array(3), idLo: new Uint32Array(3), n });
const payload = (id, n) => ({ region_id: L(id), draco: new Uint8Array([n]) });

test('the message after a gap is applied without waiting for its decodes, which may never come', async () => {
  const { decode, waiting } = deferredDecoder();
  const view = new DocumentView(1n);
  const kinds = [];
  const updates = new OrderedUpdates({
    decode, payloads: regionPayloads,
    needsRegions: (body, message) => view.needsRegions(body, message),
    apply: (body, message, decoded) => kinds.push(view.apply(body, message, decoded).kind),
  });
  updates.push('snapshot', snapshot(1, [payload(10, 1)]));
  updates.push('delta', delta(4, 5, [payload(10, 5)])); // does not follow: a gap
  updates.push('delta', delta(5, 6, [payload(10, 6)])); // its decode never answers
  updates.push('snapshot', snapshot(7, [payload(10, 7)]));
  waiting[0].resolve(fakeRegion(1));
  waiting[3].resolve(fakeRegion(7));
  await settle();
  assert.deepEqual(kinds, ['snapshot', 'gap', 'ignored', 'snapshot']);
  assert.equal(view.version, 7n);
  assert.equal(view.regions.get(10n).n, 7);
  assert.equal(updates.pending, 0);
});

test('reset drops what was queued; what comes after applies', async () => {
  const { decode, waiting } = deferredDecoder();
  let view = new DocumentView(1n);
  const applied = [];
  const updates = new OrderedUpdates({
    decode, payloads: regionPayloads,
    needsRegions: (body, message) => view.needsRegions(body, message),
    apply: (body, message, decoded) => { view.apply(body, message, decoded); applied.push(Number(view.version)); },
  });
  updates.push('snapshot', snapshot(1, [payload(10, 1)]));
  updates.push('delta', delta(1, 2, [payload(10, 2)]));
  // A new connection: a new view, and the old one's messages dropped.
  updates.reset();
  view = new DocumentView(1n);
  updates.push('snapshot', snapshot(9, [payload(10, 9)]));
  waiting[2].resolve(fakeRegion(9));
  waiting[0].resolve(fakeRegion(1));
  waiting[1].resolve(fakeRegion(2));
  await settle();
  assert.deepEqual(applied, [9]);
  assert.equal(updates.dropped, 2);
  assert.equal(view.regions.get(10n).n, 9);
});

test('a synchronous decoder applies within push, as before there was a worker', () => {
  const view = new DocumentView(1n);
  const updates = new OrderedUpdates({
    decode: (bytes) => fakeRegion(bytes[0]), payloads: regionPayloads,
    needsRegions: (body, message) => view.needsRegions(body, message),
    apply: (body, message, decoded) => view.apply(body, message, decoded),
  });
  updates.push('snapshot', snapshot(1, [payload(10, 1)]));
  assert.equal(view.version, 1n);
  updates.push('delta', delta(1, 2, [payload(10, 2)]));
  assert.equal(view.version, 2n);
  assert.equal(updates.pending, 0);
});
