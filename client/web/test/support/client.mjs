// The viewer's own Connection and DocumentSession in Node, over the TCP
// transport, plus the admin steps a test needs (create a document, grant a
// token) and waiting for a condition.
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { createWire } from '../../src/codec/wire.js';
import { Connection } from '../../src/session/connection.js';
import { DocumentSession } from '../../src/session/document_session.js';
import { decodeRegion } from '../../src/codec/region_decoder.js';
import { toLong, toBig } from '../../src/codec/uint64.js';
import { dracoDecoder } from './draco_node.mjs';
import { tcpSocketFactory } from './tcp_socket.mjs';

export const wire = createWire(readFileSync(new URL('../../../../protocol/tessera.proto', import.meta.url), 'utf8'));
const repo = (path) => new URL(`../../../../${path}`, import.meta.url);

// Polls `condition` (which may return a promise) until it gives a truthy
// value, and returns that value; throws naming `what` after `timeoutMs`.
export async function until(condition, what, timeoutMs = 15000) {
  const start = Date.now();
  for (;;) {
    const value = await condition();
    if (value) return value;
    if (Date.now() - start > timeoutMs) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 10));
  }
}

// A connection that has its HelloAck.
export async function connect(port, token, name = 'test') {
  let ack = null, error = null;
  const connection = new Connection({
    url: `tcp:${port}`, token, name, wire, createSocket: tcpSocketFactory(port),
    onReady: (a) => { ack = a; },
    onError: (text) => { error = text; },
  });
  connection.start();
  await until(() => ack || error, 'the HelloAck');
  if (!ack) throw new Error(error);
  return connection;
}

// The sample cube with its creases (deploy/samples), as a new document.
export async function createCube(admin, maxLevel = 5) {
  const reply = await admin.call({
    create_document: {
      name: 'web viewer test cube', mesh: readFileSync(repo('deploy/samples/cube.obj')), mesh_format: 1,
      tags: readFileSync(repo('deploy/samples/cube.tags'), 'utf8'), max_level: maxLevel, file_name: 'cube.obj',
    },
  });
  return toBig(reply.message.ack.document_id);
}

// A mesh file (OBJ or OFF, by its extension) as a new document.
export async function createMesh(admin, path, maxLevel) {
  const reply = await admin.call({
    create_document: {
      name: basename(path), mesh: readFileSync(path), mesh_format: path.endsWith('.off') ? 2 : 1,
      max_level: maxLevel, file_name: basename(path),
    },
  });
  return toBig(reply.message.ack.document_id);
}

export async function grant(admin, token, role, documentId = 0n) {
  await admin.call({ grant_token: { document_id: toLong(documentId), role, token } });
}

// A DocumentSession like the page's, with the events it saw recorded; with
// `view` (a View's wire fields), a view-dependent one.
export async function openSession(port, token, documentId, profile, name = 'viewer', view = null) {
  const draco = await dracoDecoder();
  const events = { views: [], errors: [], presence: 0 };
  let session = null;
  const connection = new Connection({
    url: `tcp:${port}`, token, name, wire, createSocket: tcpSocketFactory(port),
    onReady: (ack) => session.connected(ack),
    onMessage: (body, m) => session.message(body, m),
    onError: (text) => events.errors.push(text),
  });
  session = new DocumentSession({
    connection, documentId, profile, view, decode: (bytes) => decodeRegion(draco, bytes),
    onView: (change) => events.views.push(change),
    onError: (text) => events.errors.push(text),
    onPresence: () => ++events.presence,
  });
  connection.start();
  await until(() => session.view.ready || (events.errors.length > 0 && !view), 'the first snapshot');
  return { session, connection, events };
}
