// RegionBatches: a GPU buffer per region for documents of up to 2,048
// regions, so that a delta replaces exactly the changed regions' buffers;
// shared buffers for documents of many small regions. A view's tiles'
// levels and colours.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { RegionBatches, levelColour, tileLevel } from '../src/scene/region_batches.js';
import { PREVIEW_ID } from '../src/scene/tile_assembly.js';
import { tileLevels } from '../src/test_hook.js';

function region(seed) {
  // One triangle; positions differ per seed so that buffers can be told apart.
  return { positions: new Float32Array([seed, 0, 0, 0, seed, 0, 0, 0, seed]), normals: new Float32Array(9).fill(1), indices: [0, 1, 2] };
}

function tracked() {
  const built = [], dropped = [];
  const batches = new RegionBatches((b) => built.push(b), (b) => dropped.push(b));
  return { batches, built, dropped };
}

test('each region has a buffer of its own, and a delta replaces only the changed one', () => {
  const { batches, built, dropped } = tracked();
  batches.expectRegions(12);
  for (let id = 1; id <= 12; ++id) batches.set(BigInt(id), region(id));
  batches.flush();
  assert.equal(built.length, 12);
  assert.equal(batches.batches.length, 12);
  for (const b of batches.batches) assert.equal(b.regions.size, 1);
  const geometries = new Map(batches.batches.map((b) => [[...b.regions.keys()][0], b.geometry]));

  built.length = 0;
  batches.set(5n, region(50));
  batches.flush();
  assert.equal(built.length, 1, 'one buffer built for one changed region');
  assert.equal(dropped.length, 1, 'the changed region\'s old buffer dropped');
  assert.equal([...built[0].regions.keys()][0], 5n);
  assert.equal(built[0].geometry.getAttribute('position').array[0], 50);
  for (const b of batches.batches) {
    const id = [...b.regions.keys()][0];
    if (id !== 5n) assert.equal(b.geometry, geometries.get(id), `region ${id}'s buffer was rebuilt`);
  }
  batches.remove(7n);
  batches.flush();
  assert.equal(batches.batches.length, 11);
  assert.equal(batches.triangles, 11);
});

test('a document of many regions shares buffers', () => {
  const { batches } = tracked();
  batches.expectRegions(5000);
  for (let id = 1; id <= 5000; ++id) batches.set(BigInt(id), region(id));
  batches.flush();
  assert.equal(batches.batches.length, 1);
  assert.equal(batches.triangles, 5000);
});

test('tiles are coloured by level; the surface\'s preview like level 0, and counted apart by the test hook', () => {
  const cluster = (level, index) => (1n << 63n) | (BigInt(level) << 58n) | BigInt(index);
  assert.equal(tileLevel(cluster(3, 7)), 3);
  assert.equal(tileLevel((1n << 58n) | 9n), 6, 'a one-face tile: its face\'s level + 5');
  assert.equal(tileLevel(PREVIEW_ID), 0);
  assert.equal(levelColour(PREVIEW_ID).getHex(), levelColour(cluster(0, 2)).getHex());
  assert.notEqual(levelColour(PREVIEW_ID).getHex(), levelColour(cluster(8, 0)).getHex());
  const held = new Map([[PREVIEW_ID, {}], [cluster(0, 1), {}], [cluster(0, 2), {}], [cluster(2, 0), {}]]);
  assert.deepEqual(tileLevels(held), { preview: 1, 0: 2, 2: 1 });
});
