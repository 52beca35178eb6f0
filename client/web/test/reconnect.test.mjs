// Losing the server: the page's Connection retries with a growing backoff,
// and its DocumentSession opens and subscribes again, getting a fresh
// snapshot of the same document from the restarted server (its store kept
// the edits). Also: pings go out and come back. Over TCP, with the page's
// own code; skipped when the server is not built.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { startServer, serverAvailable } from './support/server.mjs';
import { connect, createCube, grant, openSession, until, wire } from './support/client.mjs';
import { Connection } from '../src/session/connection.js';
import { tcpSocketFactory } from './support/tcp_socket.mjs';

const skip = serverAvailable() ? false : 'build/release/server/tessera-server is not built';

test('after the server restarts, the session reconnects and shows the document again', { skip, timeout: 60000 }, async () => {
  let server = await startServer({ keep: true });
  const { dir, port } = server;
  const admin = await connect(port, server.token, 'admin');
  const documentId = await createCube(admin);
  await grant(admin, 'reconnect-test-editor-token', 2, documentId);
  admin.stop();
  const viewer = await openSession(port, 'reconnect-test-editor-token', documentId, { baseLevel: 1, maxLevel: 3, angle: 15 });
  await until(() => viewer.session.canEdit(), 'the editor role');
  viewer.session.moveVertex(6n, [1.1, 1.1, 1.1]);
  await until(() => viewer.session.view.version === 2n, 'the edit');
  const hash = viewer.session.view.surfaceHash();

  await server.stop();
  await until(() => !viewer.connection.connected, 'the lost connection');
  assert.match(viewer.events.errors.join('\n'), /ERROR_CODE_SHUTTING_DOWN/);
  await new Promise((r) => setTimeout(r, 1200)); // two retries fail meanwhile
  server = await startServer({ dir, port });
  await until(() => viewer.connection.ready && viewer.session.view.ready, 'the new snapshot', 20000);
  assert.ok(viewer.connection.reconnects >= 2, `${viewer.connection.reconnects} reconnections`);
  assert.equal(viewer.session.view.version, 2n, 'the durable edit is there');
  assert.equal(viewer.session.view.surfaceHash(), hash);
  assert.equal(viewer.session.lastHash.matches, true);
  viewer.connection.stop();
  await server.stop();
});

test('pings go out on their interval and are answered', { skip }, async () => {
  const server = await startServer();
  const connection = new Connection({ url: '', token: '', name: 'pinger', wire, createSocket: tcpSocketFactory(server.port), pingMs: 50 });
  connection.start();
  await until(() => connection.pongs >= 3, 'three pongs');
  connection.stop();
  await server.stop();
});
