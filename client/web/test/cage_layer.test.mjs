// The cage's lines (src/scene/cage_layer.js): the segments of the last
// update are the draw range, and a cage of more than MAX_EDGES edges is not
// drawn at all.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { CageLayer, MAX_EDGES } from '../src/scene/cage_layer.js';
import { cageEdges } from '../src/scene/control_cage.js';
import { packId } from '../src/codec/ids.js';

// A strip of `n` quads along x, counter-clockwise seen from +z: 3n + 1 edges.
function strip(n) {
  const faces = [];
  for (let i = 0; i < n; ++i) faces.push([2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1]);
  return cageEdges({ level: 1, face_sizes: faces.map((f) => f.length), vertices: faces.flat() });
}
const stripPoint = (id) => {
  const i = Number(id - packId(1, 0));
  return { position: [Math.floor(i / 2), i % 2, 0] };
};

test('the lines are the segments of the last update, redrawn on a new cage', () => {
  let changes = 0;
  const layer = new CageLayer(new THREE.Scene(), () => ++changes);
  assert.equal(layer.lines.visible, false, 'nothing before a cage');
  layer.setCage(strip(2));
  assert.equal(changes, 1);
  assert.equal(layer.lines.visible, true);
  layer.update(stripPoint, [0.5, 0.5, 4]);
  assert.equal(layer.segments, 7);
  assert.deepEqual([layer.geometry.drawRange.start, layer.geometry.drawRange.count], [0, 14]);
  assert.deepEqual([...layer.geometry.getAttribute('position').array.subarray(0, 6)], [0, 0, 0, 1, 0, 0]);
  layer.update(stripPoint, [0.5, 0.5, -4]);
  assert.equal(layer.segments, 0, 'from behind');
  assert.equal(layer.geometry.drawRange.count, 0);
  layer.setCage(null);
  assert.equal(layer.lines.visible, false);
  assert.equal(layer.segments, 0);
});

test(`beyond ${MAX_EDGES} edges nothing is drawn`, () => {
  const layer = new CageLayer(new THREE.Scene(), () => {});
  const largest = strip((MAX_EDGES - 1) / 3 | 0);
  assert.ok(largest.edges.length <= MAX_EDGES);
  layer.setCage(largest);
  assert.equal(layer.tooLarge, false);
  layer.update(stripPoint, [0, 0, 4]);
  assert.equal(layer.segments, largest.edges.length);
  const over = strip(((MAX_EDGES - 1) / 3 | 0) + 1);
  assert.ok(over.edges.length > MAX_EDGES);
  layer.setCage(over);
  assert.equal(layer.tooLarge, true);
  assert.equal(layer.lines.visible, false);
  layer.update(stripPoint, [0, 0, 4]);
  assert.equal(layer.segments, 0);
});
