// The schema-driven codec: no eval (the server's Content-Security-Policy
// forbids it, so this process forbids it too before loading anything), the
// proto3 rules the server's C++ protobuf follows, and round trips of the
// messages the viewer sends and reads.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const realFunction = globalThis.Function;
globalThis.Function = function () {
  throw new Error('eval: Function(source) was called');
};
globalThis.Function.prototype = realFunction.prototype;
const { createWire } = await import('../src/codec/wire.js');
const { toBig, toLong } = await import('../src/codec/uint64.js');
const wire = createWire(readFileSync(new URL('../../../protocol/tessera.proto', import.meta.url), 'utf8'));
const hex = (bytes) => [...bytes].map((b) => b.toString(16).padStart(2, '0')).join(' ');

test('a Snapshot with regions, a Presence and a Delta round-trip without eval', () => {
  const snapshot = wire.decodeServer(wire.encodeServer({
    snapshot: {
      document_id: toLong(3), version: toLong(9), remaining_parts: 2, resync: true, surface_hash: toLong(0xfedcba9876543210n),
      profile: { base_level: 1, max_level: 3, angle_threshold_degrees: 15, morph_t: 0 },
      regions: [{ region_id: toLong(1n << 58n), draco: new Uint8Array([1, 2, 3]) }, { region_id: toLong(5), draco: new Uint8Array(0) }],
    },
  }));
  assert.equal(snapshot.body, 'snapshot');
  const s = snapshot.snapshot;
  assert.equal(s.remaining_parts, 2);
  assert.equal(s.resync, true);
  assert.equal(toBig(s.surface_hash), 0xfedcba9876543210n);
  assert.equal(s.profile.angle_threshold_degrees, 15);
  assert.equal(s.profile.morph_t, 0, 'an optional field set to 0 is sent');
  assert.equal(s.profile.fidelity, 0);
  assert.equal(s.profile.omit_vertex_ids, false);
  assert.deepEqual(s.regions.map((r) => [toBig(r.region_id), [...r.draco]]), [[1n << 58n, [1, 2, 3]], [5n, []]]);
  const unset = wire.decodeServer(wire.encodeServer({ snapshot: { profile: {} } }));
  assert.equal(unset.snapshot.profile.morph_t, undefined, 'an unset optional stays unset');

  const presence = wire.decodeServer(wire.encodeServer({
    presence: { document_id: toLong(3), full: false, left_session_ids: [toLong(4), toLong(9)],
      participants: [{ session_id: toLong(7), name: 'bob', role: 2, selection: { vertex_ids: [toLong((1n << 58n) | 3n)] } }] },
  })).presence;
  assert.deepEqual(presence.left_session_ids.map(toBig), [4n, 9n]);
  assert.equal(presence.participants[0].name, 'bob');
  assert.equal(toBig(presence.participants[0].selection.vertex_ids[0]), (1n << 58n) | 3n);
});

test('oneofs name their set member; unset members stay undefined', () => {
  const m = wire.decodeClient(wire.encodeClient({ client_seq: toLong(4), set_vertex_type: { vertex_id: toLong(6), type: 3 } }));
  assert.equal(m.command, 'set_vertex_type');
  assert.equal(m.set_vertex_type.value, 'type');
  assert.equal(m.set_vertex_type.type, 3);
  assert.equal(m.set_vertex_type.sharpness, undefined);
  assert.equal(m.move_vertex, undefined);
});

test('proto3 leaves defaults out and packs repeated numbers', () => {
  assert.equal(hex(wire.encodeClient({ client_seq: toLong(1), hello: { protocol_version: 1, client_name: 'cli', token: '' } })),
    '00 00 00 0b 08 01 12 07 08 01 12 03 63 6c 69');
  // select{document_id 2, selection{vertex_ids [1, 2]}}: Selection's field 1 packed as 0a 02 01 02.
  assert.equal(hex(wire.encodeClient({ select: { document_id: toLong(2), selection: { vertex_ids: [toLong(1), toLong(2)] } } })),
    '00 00 00 0b 92 01 08 08 02 12 04 0a 02 01 02');
});

test('repeated numbers sent unpacked are read too; unknown fields are skipped', () => {
  // Presence{left_session_ids 4 and 9 as two varint fields, field 99 = 1}.
  const presence = new Uint8Array([0x32, 0x09, 0x20, 0x04, 0x20, 0x09, 0x98, 0x06, 0x01, 0x18, 0x01]);
  const frame = new Uint8Array([0, 0, 0, presence.length, ...presence]);
  const m = wire.decodeServer(frame);
  assert.equal(m.body, 'presence');
  assert.deepEqual(m.presence.left_session_ids.map(toBig), [4n, 9n]);
  assert.equal(m.presence.full, true);
});

test('a misspelt field is an error, not a silent default', () => {
  assert.throws(() => wire.encodeClient({ subscribe: { document: toLong(1) } }), /has no field document/);
});

test('a field running past its message is refused', () => {
  const bad = new Uint8Array([0, 0, 0, 3, 0x0a, 0x05, 0x08]);
  assert.throws(() => wire.decodeServer(bad));
});
