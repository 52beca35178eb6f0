// The viewer's protocol code against a real tessera-server (this tree's
// release build), over TCP: the page's Connection, DocumentSession,
// DocumentView, region decoder, lattice and surface hash, with the server's
// surface hash as the judge (docs/PROTOCOL.md 6.5). Skipped when the server
// is not built.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startServer, serverAvailable } from './support/server.mjs';
import { connect, createCube, createMesh, grant, openSession, until } from './support/client.mjs';
import { hex64 } from '../src/codec/uint64.js';
import { idLevel, idName } from '../src/codec/ids.js';

const skip = serverAvailable() ? false : 'build/release/server/tessera-server is not built';
let server, admin, documentId;
const editorToken = 'editor-token-for-the-web-viewer-tests';
const viewerToken = 'viewer-token-for-the-web-viewer-tests';

before(async () => {
  if (skip) return;
  server = await startServer({ extraArgs: ['--max-level', '12'] });
  admin = await connect(server.port, server.token, 'admin');
  documentId = await createCube(admin);
  await grant(admin, editorToken, 2, documentId);
  await grant(admin, viewerToken, 1, documentId);
});

after(async () => {
  admin?.stop();
  await server?.stop();
});

// Every vertex of the view with its limit position, by packed id.
function vertices(view) {
  const out = new Map();
  for (const r of view.regions.values()) {
    for (let p = 0; p < r.positions.length / 3; ++p) {
      const id = (BigInt(r.idHi[p]) << 32n) | BigInt(r.idLo[p]);
      if (!out.has(id)) out.set(id, [r.positions[3 * p], r.positions[3 * p + 1], r.positions[3 * p + 2]]);
    }
  }
  return out;
}

test('snapshots of several profiles hash to the server\'s surface hash', { skip }, async () => {
  for (const profile of [
    { baseLevel: 1, maxLevel: 3, angle: 15 }, // 8-byte or lattice ids, depth 3
    { baseLevel: 0, maxLevel: 5, angle: 7.5 }, // lattice ids, depth 5
    { baseLevel: 2, maxLevel: 2, angle: 30 },
    { baseLevel: 1, maxLevel: 3, angle: 15, omitVertexIds: true }, // display only: flag 1
  ]) {
    const { session, connection, events } = await openSession(server.port, viewerToken, documentId, profile);
    assert.deepEqual(events.errors, []);
    assert.ok(session.view.announcedHash !== 0n, 'the server sends its hash');
    assert.equal(hex64(session.view.surfaceHash()), hex64(session.view.announcedHash), JSON.stringify(profile));
    assert.ok(session.view.triangles() > 0);
    const flags = new Set([...session.view.regions.values()].map((r) => r.header.flags));
    console.log(`profile ${JSON.stringify(profile)}: ${session.view.regions.size} regions, ${session.view.triangles()} triangles, ` +
      `flags ${[...flags]}, ${session.view.regionBytes} region bytes, hash ${hex64(session.view.surfaceHash())}`);
    // Ids arrive at their birth level (6.2): none is above the profile's max level.
    if (!profile.omitVertexIds) {
      for (const id of vertices(session.view).keys()) assert.ok(idLevel(id) <= profile.maxLevel, idName(id));
    }
    connection.stop();
  }
});

test('regions deeper than a lattice can name (8-byte ids, flag 0) hash to the server\'s too', { skip }, async () => {
  // A level-10 profile over a level-10 document: flat faces stay coarse,
  // so some leaf regions lie more than 7 levels above the deepest level.
  const deep = await createCube(admin, 10);
  const profile = { baseLevel: 0, maxLevel: 10, angle: 40, budget: 200000 };
  const { session, connection, events } = await openSession(server.port, server.token, deep, profile);
  assert.deepEqual(events.errors, []);
  const flags = [...session.view.regions.values()].map((r) => r.header.flags);
  console.log(`level-10 profile: ${session.view.regions.size} regions, ${session.view.triangles()} triangles, ` +
    `${flags.filter((f) => f === 0).length} with 8-byte ids, ${flags.filter((f) => f === 4).length} with lattice ids`);
  assert.ok(flags.includes(0), 'some regions carry 8-byte ids');
  assert.equal(hex64(session.view.surfaceHash()), hex64(session.view.announcedHash));
  connection.stop();
});

test('an edit comes back as a delta whose regions reuse the layout\'s ids; undo restores the hash', { skip }, async () => {
  const profile = { baseLevel: 1, maxLevel: 4, angle: 10 };
  const editor = await openSession(server.port, editorToken, documentId, profile, 'editor');
  const watcher = await openSession(server.port, viewerToken, documentId, profile, 'watcher');
  const start = editor.session.view.surfaceHash();
  assert.equal(hex64(watcher.session.view.surfaceHash()), hex64(start));
  await until(() => editor.session.canEdit(), 'the editor role in presence');

  // Move the top corner v0:6 (1, 1, 1) up a little, in two moves of one step.
  const v06 = 6n;
  const before = vertices(editor.session.view).get(v06);
  assert.ok(before, 'v0:6 is displayed');
  const step = editor.session.history.open();
  editor.session.moveVertex(v06, [before[0], before[1], before[2] + 0.05], step);
  editor.session.moveVertex(v06, [before[0], before[1], before[2] + 0.1], step);
  editor.session.history.close(step);
  await until(() => editor.session.latency.samples >= 2 && watcher.session.view.version === editor.session.view.version &&
    editor.session.view.version >= 3n, 'both deltas at both viewers');
  assert.deepEqual(editor.events.errors, []);
  const moved = vertices(editor.session.view).get(v06);
  assert.ok(Math.abs(moved[2] - (before[2] + 0.1)) < 1e-3, `v0:6 limit z ${moved[2]}`);
  assert.equal(hex64(editor.session.view.surfaceHash()), hex64(editor.session.view.announcedHash));
  assert.equal(hex64(watcher.session.view.surfaceHash()), hex64(editor.session.view.surfaceHash()));
  const layoutOnly = editor.events.views.filter((v) => v.kind === 'delta')
    .flatMap((v) => v.changed.map((id) => editor.session.view.regions.get(id)?.header.flags)).filter((f) => f === 2).length;
  console.log(`edit-to-delta ${editor.session.latency.last.toFixed(1)} ms; regions sent without ids (flag 2): ${layoutOnly}`);

  assert.ok(editor.session.step(true), 'undo');
  await until(() => editor.session.view.version >= 5n && watcher.session.view.version >= 5n, 'the two undos');
  assert.equal(hex64(editor.session.view.surfaceHash()), hex64(start));
  assert.equal(hex64(watcher.session.view.surfaceHash()), hex64(start));
  assert.ok(editor.session.step(false), 'redo');
  await until(() => watcher.session.view.version >= 7n, 'the two redos');
  assert.equal(hex64(watcher.session.view.surfaceHash()), hex64(watcher.session.view.announcedHash));
  assert.notEqual(hex64(watcher.session.view.surfaceHash()), hex64(start));
  editor.connection.stop();
  watcher.connection.stop();
});

test('a selection shows in the other participant\'s presence; a crease and a corner change the hash', { skip }, async () => {
  const profile = { baseLevel: 1, maxLevel: 3, angle: 15 };
  const editor = await openSession(server.port, editorToken, documentId, profile, 'editor');
  const watcher = await openSession(server.port, viewerToken, documentId, profile, 'watcher');
  await until(() => editor.session.canEdit(), 'the editor role');
  editor.session.select([(1n << 58n) | 2n]);
  await until(() => watcher.session.collaborators.list().some((c) => c.selection.length === 1), 'the selection in presence');
  const names = watcher.session.collaborators.list().map((c) => c.name).sort();
  assert.deepEqual(names, ['editor', 'watcher']);
  const selected = watcher.session.collaborators.list().find((c) => c.name === 'editor').selection;
  assert.equal(idName(selected[0]), 'v1:2');

  // v0:0 and v0:1 are joined by base edge (0, 1) (the bottom rim).
  let version = watcher.session.view.version;
  const hash0 = watcher.session.view.surfaceHash();
  editor.session.setEdgeSharpness(0n, 1n, 0);
  await until(() => watcher.session.view.version > version, 'the crease delta');
  assert.notEqual(hex64(watcher.session.view.surfaceHash()), hex64(hash0));
  assert.equal(hex64(watcher.session.view.surfaceHash()), hex64(watcher.session.view.announcedHash));
  version = watcher.session.view.version;
  editor.session.setVertexType(3n, 3);
  await until(() => watcher.session.view.version > version, 'the corner delta');
  assert.equal(hex64(watcher.session.view.surfaceHash()), hex64(watcher.session.view.announcedHash));
  editor.session.setEdgeSharpness(0n, 6n, Infinity); // not joined by an edge
  await until(() => editor.events.errors.length > 0, 'the refusal');
  assert.match(editor.events.errors[0], /REJECT_REASON_INVALID_ARGUMENT/);
  editor.connection.stop();
  watcher.connection.stop();
});

test('a refused token stops the retrying and says why', { skip }, async () => {
  const { Connection } = await import('../src/session/connection.js');
  const { wire } = await import('./support/client.mjs');
  const { tcpSocketFactory } = await import('./support/tcp_socket.mjs');
  const errors = [];
  let status = '';
  const c = new Connection({ url: '', token: 'not-a-token-anyone-granted', name: 'x', wire, createSocket: tcpSocketFactory(server.port),
    onError: (t) => errors.push(t), onStatus: (s) => { status = s; } });
  c.start();
  await until(() => status === 'refused', 'the refusal', 40000);
  assert.match(errors[0], /ERROR_CODE_AUTH_FAILED/);
  assert.equal(c.stopped, true);
});

test('a catmull-clark document asked for a view is shown by its tiles, hashing to the server\'s', { skip }, async () => {
  const quads = await createMesh(admin, new URL('../../../deploy/samples/quad_cube.obj', import.meta.url).pathname, 6);
  // Close on a corner of the cube: tiles of several levels, one-face tiles
  // below level 5 among them (docs/VIEWS.md "Catmull-Clark documents").
  const view = {
    eye: { x: 1.3, y: 1.25, z: 1.35 }, forward: { x: -1, y: -1, z: -1 }, up: { x: 0, y: 0, z: 1 },
    fov_y_radians: 0.8, near_distance: 0.01, width: 1280, height: 960, tolerance_pixels: 1,
  };
  const profile = { baseLevel: 1, maxLevel: 6, angle: 15 };
  const { session, connection, events } = await openSession(server.port, server.token, quads, profile, 'viewer', view);
  await until(() => session.view.viewComplete, 'the complete view');
  assert.equal(events.errors.length, 0, events.errors.join('; '));
  assert.notEqual(session.camera, null);
  assert.ok(session.view.triangles() > 0);
  assert.equal(hex64(session.view.surfaceHash()), hex64(session.view.announcedHash));
  // A cluster tile's id has bit 63 set; a one-face tile's is its face's
  // packed id (docs/PROTOCOL.md "Views").
  const oneFace = [...session.view.regions.keys()].filter((id) => (id >> 63n) === 0n).length;
  console.log(`catmull-clark quad cube by view: ${session.view.regions.size} tiles (${oneFace} of one face), ${session.view.triangles()} triangles`);
  assert.ok(oneFace > 0, `${session.view.regions.size} tiles, none of one face`);
  connection.stop();
});
