// Framing and the schema: docs/PROTOCOL.md 2.2's example bytes, uint64
// fields beyond 2^53 kept exact, and the stream splitter of the TCP tests.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createWire, FrameSplitter } from '../src/codec/wire.js';
import { toBig, toLong } from '../src/codec/uint64.js';

const wire = createWire(readFileSync(new URL('../../../protocol/tessera.proto', import.meta.url), 'utf8'));
const hex = (bytes) => [...bytes].map((b) => b.toString(16).padStart(2, '0')).join(' ');

test('the Hello of 2.2 is 15 bytes on the wire', () => {
  const bytes = wire.encodeClient({ client_seq: toLong(1), hello: { protocol_version: 1, client_name: 'cli' } });
  assert.equal(hex(bytes), '00 00 00 0b 08 01 12 07 08 01 12 03 63 6c 69');
});

test('a Ping with client_seq 7', () => {
  assert.equal(hex(wire.encodeClient({ client_seq: toLong(7), ping: {} })), '00 00 00 05 08 07 82 01 00');
});

test('uint64 ids above 2^53 survive a round trip', () => {
  const id = (3n << 58n) | 1234n; // v3:1234 = 864691128455136466
  const bytes = wire.encodeClient({ client_seq: toLong(2), select: { document_id: toLong(5), selection: { vertex_ids: [toLong(id)] } } });
  const back = wire.decodeClient(bytes);
  assert.equal(wire.commandOf(back), 'select');
  assert.equal(toBig(back.select.selection.vertex_ids[0]), 864691128455136466n);
  const all = (1n << 64n) - 1n;
  const edge = wire.decodeClient(wire.encodeClient({ set_edge_sharpness: { edge_id: toLong(all) } }));
  assert.equal(toBig(edge.set_edge_sharpness.edge_id), all);
});

test('server messages: the body and unset fields read as their defaults', () => {
  const bytes = wire.encodeServer({ delta: { document_id: toLong(1), from_version: toLong(4), to_version: toLong(5) } });
  const m = wire.decodeServer(bytes);
  assert.equal(wire.bodyOf(m), 'delta');
  assert.equal(toBig(m.delta.to_version), 5n);
  assert.equal(toBig(m.delta.surface_hash), 0n);
  assert.deepEqual(m.delta.regions, []);
});

test('a frame whose prefix disagrees with its length is refused', () => {
  const bytes = wire.encodeClient({ client_seq: toLong(7), ping: {} });
  assert.throws(() => wire.decodeServer(bytes.subarray(0, 6)), /announces 5 bytes but carries 2/);
  assert.throws(() => wire.decodeServer(new Uint8Array([0, 0, 0, 0])), /0 bytes/);
});

test('the splitter cuts a stream into whole frames however it arrives', () => {
  const a = wire.encodeClient({ client_seq: toLong(1), ping: {} });
  const b = wire.encodeClient({ client_seq: toLong(2), hello: { protocol_version: 1 } });
  const stream = new Uint8Array([...a, ...b]);
  const splitter = new FrameSplitter();
  const frames = [];
  for (let i = 0; i < stream.length; i += 3) frames.push(...splitter.push(stream.subarray(i, i + 3)));
  assert.deepEqual(frames.map(hex), [hex(a), hex(b)]);
});
