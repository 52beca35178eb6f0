// window.tesseraViewer: what the headless-browser tests read and do
// (client/web/README.md "Test hook"). Plain JSON values only: ids as text
// ("v2:123") and decimal strings, hashes as "0x" + 16 hex digits.
import { idName, packId, parseIdName } from './codec/ids.js';
import { hex64 } from './codec/uint64.js';
import { tileLevel } from './scene/region_batches.js';
import { isPreview } from './scene/tile_assembly.js';
import { DRACO_LOADED_MARK } from './codec/decode_messages.js';

// The surface's preview counts as "preview", not as a level.
export function tileLevels(regions) {
  const out = {};
  for (const id of regions.keys()) {
    const level = isPreview(id) ? 'preview' : String(tileLevel(id));
    out[level] = (out[level] ?? 0) + 1;
  }
  return out;
}

export function regionCodecs(regions) {
  const out = {};
  for (const r of regions.values()) {
    const codec = r.header?.codec ?? 'draco';
    out[codec] = (out[codec] ?? 0) + 1;
  }
  return out;
}

const ROLE_NAMES = ['ROLE_UNSPECIFIED', 'ROLE_VIEWER', 'ROLE_EDITOR', 'ROLE_ADMIN'];

// app: {page (PageState), view (SceneView), picker, vertices, editor, cage (CageControl)}
export function installTestHook(app) {
  const { page } = app;
  const hook = {
    state() {
      const { connection, session } = page;
      const view = session?.view;
      const hash = session?.lastHash;
      return {
        connected: Boolean(connection?.ready),
        ready: page.ready,
        role: ROLE_NAMES[session ? session.role : connection?.helloAck?.role ?? 0] ?? String(session?.role),
        documentId: session ? String(session.documentId) : '',
        version: view ? Number(view.version) : 0,
        surfaceHash: hash ? hex64(hash.ours) : hex64(0n),
        serverSurfaceHash: hash ? hex64(hash.server) : hex64(0n),
        hashMatches: Boolean(hash?.matches),
        triangles: view ? view.triangles() : 0,
        // The codec subscribed with (?codec=, then the panel), and the
        // regions held by the codec they came in ({"draco": n, "meshopt": m}).
        codec: page.codec,
        regionCodecs: view ? regionCodecs(view.regions) : {},
        regions: view ? view.regions.size : 0,
        // Whether the page subscribes with a view (main.js); then whether
        // the latest camera's tiles are all here, the tiles held by level
        // ("level": count, the preview as "preview"), their ids, and the
        // ids of the regions drawn (the preview alone while it is held).
        views: page.views,
        viewComplete: session ? session.viewComplete() : false,
        tileLevels: view ? tileLevels(view.regions) : {},
        tiles: view ? [...view.regions.keys()].map(String).sort().join(' ') : '',
        shown: app.view.shownIds().map(String).sort().join(' '),
        firstPicture: page.firstPicture,
        milestones: page.milestones,
        firstSnapshot: view ? view.firstSnapshot : null,
        bytesReceived: connection ? connection.bytesReceived : 0,
        lastEditToDeltaMs: session?.latency.last ?? null,
        collaborators: session ? session.collaborators.list().map((c) => ({
          sessionId: String(c.sessionId),
          name: c.name,
          role: ROLE_NAMES[c.role] ?? String(c.role),
          selection: c.selection.map((id) => idName(id)),
          self: c.sessionId === session.sessionId,
        })) : [],
        error: page.lastError,
        frames: connection ? connection.frames : 0,
        editsSent: session?.editsSent ?? 0,
        editsRejected: session?.editsRejected ?? 0,
        awaitingAnswers: session?.history.awaitingAnswers() ?? 0,
        editLevel: app.editor.level,
        picked: app.editor.picks.map((id) => idName(id)),
        // The control cage (docs/WEB_VIEWER.md "The control cage"):
        // {on, level, status, faces, edges (unique), faceSizes ({"4": 6}:
        // faces by corners), segments (drawn in the last frame), requests
        // (GetCage sent)}.
        cage: app.cage.facts(),
        // Region payloads decode in a Web Worker (docs/WEB_VIEWER.md
        // "Decoding in a worker"): {workers, decoded, failed, waiting,
        // meanMs, p99Ms, workerDraco, mainThreadDraco, messagesApplied,
        // messagesWaiting}; mainThreadDraco is whether this thread ever
        // created a Draco module (it should not).
        decoding: {
          ...(page.decoder ? page.decoder.facts() : {}),
          mainThreadDraco: globalThis[DRACO_LOADED_MARK] === true,
          messagesApplied: session?.updates.applied ?? 0,
          messagesWaiting: session?.updates.pending ?? 0,
        },
      };
    },

    // CSS pixels of the page where the vertex is drawn, or null when it is
    // not displayed or behind the camera. Any level of the vertex's id.
    screenPointOfVertex(idString) {
      const id = parseIdName(idString);
      const vertex = id === null ? null : app.vertices.lookup(id);
      if (!vertex) return null;
      return app.picker.toScreen(vertex.position);
    },

    // Turns the camera round its target about the world's up axis, as an
    // orbiting drag would (a view-dependent subscription then sends it).
    orbitBy(radians) {
      const { camera, controls } = app.view;
      const offset = camera.position.clone().sub(controls.target);
      offset.applyAxisAngle({ x: 0, y: 1, z: 0, isVector3: true }, radians);
      camera.position.copy(controls.target).add(offset);
      camera.lookAt(controls.target);
      controls.update();
      app.view.invalidate();
    },

    // Moves the camera along its line of sight to `factor` of its distance.
    dolly(factor) {
      const { camera, controls } = app.view;
      const offset = camera.position.clone().sub(controls.target).multiplyScalar(factor);
      camera.position.copy(controls.target).add(offset);
      controls.update();
      app.view.invalidate();
    },

    // A visible control vertex of the edit level near the middle of the
    // canvas: the one a click there would pick.
    someVertexNearCentre() {
      const found = app.picker.nearCentre(app.editor.level);
      if (!found) return null;
      const id = packId(app.editor.level, found.vertex.index);
      return { id: idName(id), packed: String(id), x: found.screen.x, y: found.screen.y };
    },

    renderedFrames() {
      return app.view.frames;
    },

    // The decode worker's answers, one per WebSocket message decoded (a
    // snapshot part or a delta), oldest first: [{regions, meshopt, bytes,
    // ms}] (codec/decode_pool.js).
    decodeBatches() {
      return page.decoder ? page.decoder.batches.slice() : [];
    },

    // [version, Unix ms of the first frame drawn at it] for the versions
    // drawn lately (a version merged into a later delta is never drawn).
    versionsShown() {
      return [...page.shownAt.entries()].map(([v, at]) => [Number(v), at]);
    },
  };
  window.tesseraViewer = hook;
  return hook;
}
