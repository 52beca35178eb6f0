// Version continuity (docs/PROTOCOL.md 6.1), as client/lib/document_view.cc
// applies it, with a stand-in decoder: snapshot parts, deltas that follow,
// gaps, layout ids, and the edit-to-delta latency measured across them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import Long from 'long';
import { DocumentView } from '../src/session/document_view.js';
import { LatencyTracker } from '../src/session/latency.js';
import { PREVIEW_ID, shownTiles } from '../src/scene/tile_assembly.js';

const L = (n) => Long.fromValue(n, true);
// A payload here is [flags, layoutVersion, ...indices]; decoding gives a
// region with one id per index and the header fields the view reads.
function decode(bytes) {
  const [flags, layout, ...indices] = bytes;
  const idsInline = flags !== 2;
  const n = Math.max(...indices) + 1;
  return {
    header: { idsInline, hasIds: flags !== 1, layoutVersion: BigInt(layout), regionId: 0n, documentVersion: 0n },
    positions: new Float32Array(3 * n), normals: new Float32Array(3 * n), indices: new Uint32Array(indices),
    idHi: idsInline ? new Uint32Array(n) : null, idLo: idsInline ? new Uint32Array(n).map((_, i) => 100 + i) : null,
  };
}
const region = (id, ...bytes) => ({ region_id: L(id), draco: new Uint8Array(bytes) });
const snapshot = (version, regions, remaining = 0) => ({ snapshot: { document_id: L(1), version: L(version), regions, remaining_parts: remaining, surface_hash: L(0), resync: false } });
const delta = (from, to, regions, removed = []) => ({ delta: { document_id: L(1), from_version: L(from), to_version: L(to), regions, removed_region_ids: removed.map(L), surface_hash: L(0), author_session_id: L(5), edit_id: L(3) } });

test('parts wait for the last; then deltas that follow apply, in order', () => {
  const view = new DocumentView(1n, decode);
  assert.equal(view.apply('delta', delta(3, 4, [])).kind, 'ignored', 'no snapshot yet');
  assert.equal(view.apply('snapshot', snapshot(4, [region(10, 0, 1, 0, 1, 2)], 1)).kind, 'part');
  assert.equal(view.ready, false);
  const whole = view.apply('snapshot', snapshot(4, [region(11, 0, 1, 0, 1, 2)]));
  assert.equal(whole.kind, 'snapshot');
  assert.deepEqual([...view.regions.keys()], [10n, 11n]);
  assert.equal(view.version, 4n);
  const d = view.apply('delta', delta(4, 6, [region(10, 0, 5, 0, 1, 2, 2, 1, 3)], [11]));
  assert.equal(d.kind, 'delta');
  assert.deepEqual(d.changed, [10n]);
  assert.deepEqual(d.removed, [11n]);
  assert.equal(view.version, 6n);
  assert.equal(view.triangles(), 2);
});

test('a delta that does not follow is a gap: the view waits for a snapshot', () => {
  const view = new DocumentView(1n, decode);
  view.apply('snapshot', snapshot(4, [region(10, 0, 1, 0, 1, 2)]));
  assert.equal(view.apply('delta', delta(5, 6, [])).kind, 'gap');
  assert.equal(view.ready, false);
  assert.equal(view.gaps, 1);
  assert.equal(view.apply('delta', delta(4, 5, [])).kind, 'ignored');
  assert.equal(view.apply('snapshot', snapshot(7, [region(10, 0, 1, 0, 1, 2)])).kind, 'snapshot');
  assert.equal(view.apply('delta', delta(7, 8, [])).kind, 'delta');
});

test('a region without ids takes the held layout\'s, also from earlier in the same delta', () => {
  const view = new DocumentView(1n, decode);
  view.apply('snapshot', snapshot(4, [region(10, 0, 1, 0, 1, 2)]));
  assert.equal(view.apply('delta', delta(4, 5, [region(10, 2, 1, 0, 1, 2)])).kind, 'delta');
  assert.equal(view.regions.get(10n).idLo[2], 102);
  // A new layout, then a moved copy of it, in one merged delta.
  assert.equal(view.apply('delta', delta(5, 7, [region(10, 0, 6, 0, 2, 1), region(10, 2, 6, 0, 2, 1)])).kind, 'delta');
  assert.equal(view.regions.get(10n).header.layoutVersion, 6n);
  // A layout the view does not hold: a gap.
  assert.equal(view.apply('delta', delta(7, 8, [region(10, 2, 3, 0, 2, 1)])).kind, 'gap');
});

test('a snapshot region without ids cannot be assembled', () => {
  const view = new DocumentView(1n, decode);
  assert.equal(view.apply('snapshot', snapshot(4, [region(10, 2, 1, 0, 1, 2)])).kind, 'gap');
});

test('latency: from sending to the delta that brings the acked version, whichever comes first', () => {
  let now = 0;
  const t = new LatencyTracker(() => now);
  t.acked(5n, 0, 4n); // the Ack first
  now = 30;
  t.delta(4n, 6n, true);
  assert.equal(t.last, 30);
  now = 50;
  t.delta(6n, 7n, true); // the delta first
  now = 90;
  t.acked(7n, 20, 7n);
  assert.equal(t.last, 30, 'arrival 50 - sent 20');
  assert.equal(t.samples, 2);
});

test('a view\'s first snapshot may be the surface\'s preview: drawn alone until a delta removes it', () => {
  // docs/VIEWS.md "The first picture": the tiles come as deltas meanwhile, and are
  // held and decoded, but not drawn.
  const view = new DocumentView(1n, decode);
  const preview = region(PREVIEW_ID, 0, 1, 0, 1, 2, 0, 2, 3);
  assert.equal(view.apply('snapshot', snapshot(4, [preview])).kind, 'snapshot');
  assert.equal(view.regions.get(PREVIEW_ID).bytes, preview.draco.length, 'each region keeps its payload\'s size');
  assert.deepEqual([...shownTiles(view.regions).keys()], [PREVIEW_ID]);
  view.apply('delta', delta(4, 4, [region(10, 0, 1, 0, 1, 2)]));
  assert.equal(view.regions.size, 2);
  assert.deepEqual([...shownTiles(view.regions).keys()], [PREVIEW_ID], 'a tile arrived: the preview still alone');
  view.apply('delta', delta(4, 4, [region(11, 0, 1, 0, 1, 2)], [PREVIEW_ID]));
  assert.deepEqual([...shownTiles(view.regions).keys()], [10n, 11n]);
  // The first snapshot stays as it came, for the test hook.
  assert.deepEqual(view.firstSnapshot, { ids: [String(PREVIEW_ID)], bytes: preview.draco.length, triangles: 2 });
  view.apply('snapshot', snapshot(5, [region(12, 0, 1, 0, 1, 2)]));
  assert.deepEqual(view.firstSnapshot.ids, [String(PREVIEW_ID)], 'a later snapshot leaves it');
});
