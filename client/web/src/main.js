// The page: reads ?doc= and #token=, connects to /ws, opens the document
// and shows it, and wires the parts together: Connection -> DocumentSession
// -> SceneView (+ VertexIndex, markers) -> Hud; Editor turns input into
// commands; the test hook exposes the state.
import protoText from './codec/proto_text.js';
import { createWire } from './codec/wire.js';
import { Connection } from './session/connection.js';
import { DocumentSession } from './session/document_session.js';
import { decodeRegion } from './codec/region_decoder.js';
import { loadDracoFrom } from './codec/draco.js';
import { SceneView } from './scene/scene.js';
import { VertexIndex } from './scene/vertex_index.js';
import { Picker } from './scene/picking.js';
import { ControlPointsLayer } from './scene/control_points.js';
import { PresenceLayer } from './scene/presence_layer.js';
import { Editor } from './ui/editing.js';
import { Hud } from './ui/hud.js';
import { StartPanel } from './ui/start_panel.js';
import { presetNamed, DEFAULT_PRESET } from './session/lod_profiles.js';
import { readPageParams, webSocketUrl, addressWithDocument } from './ui/page_params.js';
import { installTestHook } from './test_hook.js';
import { toBig } from './codec/uint64.js';

const HUD_INTERVAL_MS = 250;

function setPageState(state) {
  document.body.dataset.state = state;
}

// Into the fragment, without the hashchange that means "the user typed
// another token" (main() reloads on that).
function setTokenInAddress(token) {
  window.history.replaceState(null, '', `${window.location.pathname}${window.location.search}#token=${encodeURIComponent(token)}`);
}

async function main() {
  setPageState('loading');
  window.addEventListener('hashchange', () => window.location.reload());
  const params = readPageParams(window.location);
  const wire = createWire(protoText);
  const view = new SceneView(document.getElementById('stage'));
  const vertices = new VertexIndex();
  const picker = new Picker(view, vertices);
  const controlPoints = new ControlPointsLayer(view.scene, () => view.invalidate());
  const presence = new PresenceLayer(view.scene, () => view.invalidate());
  const start = new StartPanel(document.getElementById('start'));

  let connection = null, session = null, draco = null;
  let profile = { ...presetNamed(params.lod ?? DEFAULT_PRESET) };
  let status = 'starting', lastError = '', documentName = '';
  let readyAfterRender = false, ready = false;
  const showError = (text) => { lastError = text; };

  const refreshMarkers = () => {
    controlPoints.setVertices(vertices.atLevel(editor.level));
    const others = session ? session.collaborators.list().filter((c) => c.sessionId !== session.sessionId) : [];
    presence.update(others, editor.picks, (id) => vertices.lookup(id)?.position ?? null);
  };

  const hud = new Hud(document.getElementById('hud'), {
    onPreset: (name) => {
      profile = { ...presetNamed(name) };
      session?.subscribeOrShallower(profile).catch((e) => showError(`subscribe: ${e.message}`));
    },
    onWireframe: (on) => view.setWireframe(on),
    onRegionColours: (on) => view.setRegionColours(on),
    onLevel: (delta) => { editor.setLevel(editor.level + delta); refreshMarkers(); },
  });

  const editor = new Editor({
    element: view.renderer.domElement, view, picker, vertices, controlPoints,
    session: () => session,
    maxLevel: () => profile.maxLevel,
    onChange: refreshMarkers,
    onError: showError,
    toggleHud: () => hud.toggle(),
  });
  editor.clampLevel();

  // When each version was first drawn (Unix ms, Date.now()): the
  // benchmark times edit-to-pixels against the editor's clock with it
  // (bench/web_viewer_bench.mjs). The last 4,096 versions.
  const shownAt = new Map();
  let shownVersion = -1n;
  installTestHook({
    connection: () => connection, session: () => session, view, picker, vertices, editor,
    lastError: () => lastError, ready: () => ready, shownAt: () => shownAt,
  });

  function openDocument(documentId, helloAck) {
    session = new DocumentSession({
      connection, documentId, profile,
      decode: (bytes) => decodeRegion(draco, bytes),
      onView: (change) => {
        view.apply(change, session.view.regions);
        vertices.apply(change, session.view.regions);
        editor.refreshHover();
        refreshMarkers();
        if (change.kind === 'snapshot') readyAfterRender = true;
      },
      onPresence: refreshMarkers,
      onProfile: (p) => { profile = p; editor.clampLevel(); },
      onStatus: (s) => { status = s; },
      onError: showError,
    });
    start.hide();
    session.connected(helloAck);
  }

  async function chooseDocument(helloAck) {
    try {
      const reply = await connection.call({ list_documents: {} });
      const documents = reply.message.document_list.documents.map((d) => ({
        id: toBig(d.document_id), name: d.name, version: toBig(d.version),
      }));
      if (params.documentId !== null) {
        documentName = documents.find((d) => d.id === params.documentId)?.name ?? '';
        return;
      }
      setPageState('choosing');
      start.listDocuments(documents, (id) => {
        window.history.replaceState(null, '', addressWithDocument(window.location, id));
        params.documentId = id;
        documentName = documents.find((d) => d.id === id)?.name ?? '';
        openDocument(id, helloAck);
      });
    } catch (error) {
      showError(`list documents: ${error.message}`);
    }
  }

  function begin(token) {
    start.message('Connecting…');
    connection = new Connection({
      url: webSocketUrl(window.location), token, name: params.name, wire,
      createSocket: (url) => new WebSocket(url),
      onReady: (helloAck) => {
        lastError = '';
        if (params.documentId !== null) {
          if (session) session.connected(helloAck); else openDocument(params.documentId, helloAck);
        }
        chooseDocument(helloAck);
      },
      onMessage: (body, message) => session?.message(body, message),
      onStatus: (s) => { status = s; },
      onError: (text, fatal) => {
        showError(text);
        if (connection?.permanentError) {
          setPageState('error');
          start.askToken((t) => { setTokenInAddress(t); window.location.reload(); }, text);
        } else if (fatal) {
          status = 'the server closed the connection';
        }
      },
      onClosed: () => {
        ready = false;
        if (document.body.dataset.state === 'ready') setPageState('connecting');
      },
    });
    setPageState('connecting');
    connection.start();
  }

  // The render loop: an animation frame is asked for only when something
  // changed (view.invalidate(), the camera's controls), and a drawn frame
  // asks for the next while the camera still moves (damping). An idle page
  // asks for none: a page that asks at every frame keeps the browser's
  // compositor busy, which under a software renderer cost most of a core
  // for twenty idle tabs. The HUD is refreshed four times a second on a
  // timer (the DOM costs more than a frame of a small model); the frame
  // rate counts the frames drawn in each half second, 0 when idle.
  let fps = 0, fpsFrames = 0, fpsAt = performance.now(), bytesAt = 0, bytesSampleAt = fpsAt, bytesPerSecond = 0;
  let frameAsked = false;
  const askFrame = () => {
    if (frameAsked) return;
    frameAsked = true;
    requestAnimationFrame(frame);
  };
  const frame = () => {
    frameAsked = false;
    const drew = view.renderIfNeeded();
    if (!drew) return;
    ++fpsFrames;
    askFrame();
    if (session?.view.ready && session.view.version !== shownVersion) {
      shownVersion = session.view.version;
      shownAt.set(String(shownVersion), Date.now());
      if (shownAt.size > 4096) shownAt.delete(shownAt.keys().next().value);
    }
    if (readyAfterRender) {
      readyAfterRender = false;
      ready = true;
      setPageState('ready');
    }
  };
  view.onInvalidate = askFrame;
  askFrame();
  const hudTick = () => {
    const now = performance.now();
    if (now - fpsAt >= 500) {
      fps = (fpsFrames * 1000) / (now - fpsAt);
      fpsFrames = 0;
      fpsAt = now;
    }
    if (now - bytesSampleAt >= 1000 && connection) {
      bytesPerSecond = ((connection.bytesReceived - bytesAt) * 1000) / (now - bytesSampleAt);
      bytesAt = connection.bytesReceived;
      bytesSampleAt = now;
    }
    hud.update({
      fps, triangles: view.triangles, regions: session?.view.regions.size ?? 0,
      version: session?.view.version ?? 0n, documentId: session?.documentId ?? null, documentName,
      role: session?.role ?? connection?.helloAck?.role ?? 0, latencyMs: session?.latency.last ?? null,
      bytesPerSecond, hash: session?.lastHash ?? null, preset: profile.name?.split(' ')[0] ?? DEFAULT_PRESET,
      wireframe: view.wireframe, regionColours: view.regionColours, level: editor.level,
      pick: editor.describe(), points: controlPoints.count ?? 0, pointsDrawn: controlPoints.drawn,
      people: session ? session.collaborators.list().map((c) => ({ ...c, self: c.sessionId === session.sessionId })) : [],
      status: connection?.ready && session?.view.ready ? 'live' : status,
      error: lastError,
    });
  };
  setInterval(hudTick, HUD_INTERVAL_MS);

  try {
    draco = (await loadDracoFrom('draco_decoder.wasm')).draco;
  } catch (error) {
    showError(error.message);
    setPageState('error');
    start.message(`The Draco decoder did not load: ${error.message}`);
    return;
  }
  if (params.token) {
    begin(params.token);
  } else {
    setPageState('token');
    start.askToken((token) => {
      setTokenInAddress(token);
      begin(token);
    });
  }
}

main();
