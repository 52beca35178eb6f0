// Small region payloads for the decoding tests: one triangle refined once
// (6 points, 4 faces) with 8-byte ids (flag 0), bent by `version` so that
// the versions of a region differ, made with draco3d's encoder.
import { packId } from '../../src/codec/ids.js';
import { encodeTestRegion } from './region_encoder.mjs';

const grid = { origin: [-2, -2, -2], range: 4, positionBits: 14, normalBits: 10 };
const points = [[0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]];
const faces = [0, 3, 5, 3, 1, 4, 5, 4, 2, 4, 5, 3];

export function testRegion(enc, regionId, version) {
  const positions = points.flatMap(([u, v]) => [u * 0.5, v * 0.5, 0.1 * Number(version) * u * v]);
  const normals = points.flatMap(() => [0, 0, 1]);
  const ids = points.map((_, i) => packId(i < 3 ? 0 : 1, i));
  return encodeTestRegion(enc, { flags: 0, regionId, documentVersion: version, layoutVersion: 1n, maxLevel: 1, grid },
    { positions, normals, faces, ids });
}
