// The page's side of its decode worker (src/codec/decode_pool.js) with a
// stand-in worker: regions come back as decodeRegion() makes them, their
// arrays transferred (the worker's copies detached); an answer may come in
// any order and finds its own request; a bad payload rejects with the
// synchronous decoder's own message; a worker that stops fails everything
// waiting and everything after, once. What is asked in one task goes to a
// worker as one message.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DecodePool } from '../src/codec/decode_pool.js';
import { packAnswers } from '../src/codec/decode_messages.js';
import { decodeRegion } from '../src/codec/region_decoder.js';
import { dracoDecoder, dracoEncoder } from './support/draco_node.mjs';
import { encodeTestRegion } from './support/region_encoder.mjs';
import { FakeDecodeWorker } from './support/fake_decode_worker.mjs';
import { testRegion } from './support/test_regions.mjs';

const taskEnd = () => new Promise((resolve) => setImmediate(resolve));

test('regions come back decoded as on the main thread, their arrays transferred, each to its own request', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const worker = new FakeDecodeWorker(draco);
  const pool = new DecodePool({ createWorker: () => worker });
  worker.start();
  await pool.ready;
  const a = testRegion(enc, 10n, 1n), b = testRegion(enc, 11n, 1n);
  const frame = new Uint8Array(a.length + b.length);
  frame.set(a);
  frame.set(b, a.length);
  // Views into one frame, as the wire's regions are: the frame stays whole.
  const pa = pool.decode(frame.subarray(0, a.length)), pb = pool.decode(frame.subarray(a.length));
  assert.equal(worker.requests.length, 0, 'sent once the task ends');
  await taskEnd();
  assert.equal(worker.messages, 1, 'both in one message');
  assert.equal(worker.requests.length, 2);
  assert.equal(frame.byteLength, a.length + b.length, 'the frame is not detached');
  worker.answer(1);
  worker.answer(0);
  const [ra, rb] = await Promise.all([pa, pb]);
  assert.equal(ra.header.regionId, 10n);
  assert.equal(rb.header.regionId, 11n);
  const expected = decodeRegion(draco, a);
  for (const key of ['positions', 'normals', 'indices', 'idHi', 'idLo']) assert.deepEqual(ra[key], expected[key], key);
  for (const sent of worker.sentRegions) {
    assert.equal(sent.positions.byteLength, 0, 'the worker\'s positions were transferred, not copied');
    assert.equal(sent.idLo.byteLength, 0, 'and its ids');
  }
  const facts = pool.facts();
  assert.equal(facts.decoded, 2);
  assert.equal(facts.waiting, 0);
  assert.equal(facts.workerDraco, true);
  assert.equal(facts.meanMs, 1);
});

test('a corrupted payload rejects with the message the synchronous decoder throws', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const worker = new FakeDecodeWorker(draco);
  const pool = new DecodePool({ createWorker: () => worker });
  worker.start();
  const bytes = testRegion(enc, 10n, 2n);
  bytes[bytes.length - 9] ^= 0x40; // inside the Draco bytes: the checksum no longer holds
  let expected;
  assert.throws(() => decodeRegion(draco, bytes), (error) => { expected = error.message; return true; });
  assert.match(expected, /checksum mismatch/);
  const decoding = pool.decode(bytes);
  await taskEnd();
  worker.answer();
  await assert.rejects(decoding, (error) => error instanceof Error && error.message === expected);
  assert.equal(pool.facts().failed, 1);
});

test('a worker that stops fails what waits and what comes after, and says so once', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const workers = [new FakeDecodeWorker(draco), new FakeDecodeWorker(draco)];
  const failures = [];
  let next = 0;
  const pool = new DecodePool({ createWorker: () => workers[next++], size: 2, onFailure: (e) => failures.push(e.message) });
  const waiting = [pool.decode(testRegion(enc, 10n, 1n)), pool.decode(testRegion(enc, 11n, 1n))];
  await taskEnd();
  assert.deepEqual(workers.map((w) => w.requests.length), [1, 1], 'the fewest waiting gets the next');
  workers[1].crash('out of memory');
  workers[0].crash('out of memory');
  for (const p of waiting) await assert.rejects(p, /the decode worker stopped: out of memory/);
  await assert.rejects(pool.ready, /the decode worker stopped/);
  await assert.rejects(pool.decode(testRegion(enc, 12n, 1n)), /the decode worker stopped/);
  assert.deepEqual(failures, ['the decode worker stopped: out of memory']);
});

test('a worker whose Draco module does not load fails its start', async () => {
  const worker = new FakeDecodeWorker(null);
  const pool = new DecodePool({ createWorker: () => worker });
  worker.deliver({ loadFailed: 'the Draco decoder draco_decoder.wasm: HTTP 404' });
  await assert.rejects(pool.ready, /HTTP 404/);
});

test('a message\'s regions travel in one buffer: each array a view of it, with its own values', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const regions = [decodeRegion(draco, testRegion(enc, 10n, 1n)), decodeRegion(draco, testRegion(enc, 11n, 2n))];
  const expected = regions.map((r) => ({ ...r, positions: r.positions.slice(), idLo: r.idLo.slice(), indices: r.indices.slice() }));
  const answers = [{ id: 1, region: regions[0], ms: 1 }, { id: 2, error: 'region 12: checksum mismatch', ms: 1 }, { id: 3, region: regions[1], ms: 1 }];
  const transfer = packAnswers(answers);
  assert.equal(transfer.length, 1);
  const arrived = structuredClone({ answers }, { transfer }).answers;
  assert.equal(transfer[0].byteLength, 0, 'transferred, not copied');
  const buffer = arrived[0].region.positions.buffer;
  for (const i of [0, 2]) {
    const r = arrived[i].region, e = expected[i / 2];
    for (const key of ['positions', 'normals', 'indices', 'idHi', 'idLo']) assert.equal(r[key].buffer, buffer, key);
    assert.deepEqual(r.positions, e.positions);
    assert.deepEqual(r.indices, e.indices);
    assert.deepEqual(r.idLo, e.idLo);
  }
  assert.equal(arrived[1].error, 'region 12: checksum mismatch');
});
