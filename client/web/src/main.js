// The page: reads ?doc= and #token=, connects to /ws, opens the document
// and shows it, and wires the parts together: Connection -> DocumentSession
// -> SceneView (+ VertexIndex, markers, the control cage) -> Hud; Editor
// turns input into commands; in a test build, the test hook exposes the
// state.
import protoText from './codec/proto_text.js';
import { createWire } from './codec/wire.js';
import { Connection } from './session/connection.js';
import { DocumentSession } from './session/document_session.js';
import { DecodePool } from './codec/decode_pool.js';
import { SceneView } from './scene/scene.js';
import { VertexIndex } from './scene/vertex_index.js';
import { Picker } from './scene/picking.js';
import { ControlPointsLayer } from './scene/control_points.js';
import { CageLayer } from './scene/cage_layer.js';
import { PresenceLayer } from './scene/presence_layer.js';
import { Editor } from './ui/editing.js';
import { CageControl } from './ui/cage_control.js';
import { Hud } from './ui/hud.js';
import { StartPanel } from './ui/start_panel.js';
import { presetNamed, DEFAULT_PRESET } from './session/lod_profiles.js';
import { readPageParams, webSocketUrl, addressWithDocument } from './ui/page_params.js';
import { installTestHook } from './test_hook.js';
import { toBig } from './codec/uint64.js';
import { PageState } from './page_state.js';
import { viewOfCamera, ViewSender } from './session/view_camera.js';
import { PREVIEW_ID } from './scene/tile_assembly.js';

const HUD_INTERVAL_MS = 250;
// Region payloads decode in one Web Worker (docs/WEB_VIEWER.md "Decoding in
// a worker"): it keeps the main thread free for input and drawing, and one
// per page keeps many open tabs from holding a Draco module per core each.
const DECODE_WORKERS = 1;

function setBodyState(state) {
  document.body.dataset.state = state;
}

// Into the fragment, without the hashchange that means "the user typed
// another token" (main() reloads on that).
function setTokenInAddress(token) {
  window.history.replaceState(null, '', `${window.location.pathname}${window.location.search}#token=${encodeURIComponent(token)}`);
}

async function main() {
  setBodyState('loading');
  window.addEventListener('hashchange', () => window.location.reload());
  const params = readPageParams(window.location);
  // The decode worker starts first: it fetches draco_decoder.wasm and
  // instantiates it (this thread never does) while this thread builds the
  // scene and connects. The worker holds the payloads it is sent until its
  // decoders are ready, so the page need not wait for them: on a network,
  // the HelloAck, the subscription and the server's first answers overlap
  // the module's download and compilation (docs/PERFORMANCE.md "The page's
  // first second").
  const decoder = new DecodePool({
    createWorker: () => new Worker('decode_worker.js', { name: 'tessera region decoder' }),
    size: DECODE_WORKERS,
    onFailure: (error) => decodingFailed(error),
  });
  const wire = createWire(protoText);
  const view = new SceneView(document.getElementById('stage'), params.views);
  // A view-dependent subscription (the default, docs/WEB_VIEWER.md "Views"):
  // the camera goes to the server as it moves (session/view_camera.js); X
  // freezes it.
  const cameraView = (tolerance) => {
    view.camera.updateMatrixWorld();
    const canvas = view.renderer.domElement;
    return viewOfCamera(view.camera, canvas.clientWidth || 1, canvas.clientHeight || 1, tolerance);
  };
  const sender = new ViewSender((v) => page.session?.setView(v) ?? false);
  let offerTimer = null;
  const offerView = () => {
    if (!page.views || !view.fitted || !page.session) return;
    if (sender.offer(cameraView(params.tolerance)) && !offerTimer) {
      offerTimer = setTimeout(() => { offerTimer = null; offerView(); }, 60);
    }
  };
  window.addEventListener('keydown', (e) => {
    if (!page.views || (e.key !== 'x' && e.key !== 'X')) return;
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
    sender.frozen = !sender.frozen;
    if (!sender.frozen) offerView();
  });
  const vertices = new VertexIndex();
  const picker = new Picker(view, vertices);
  const controlPoints = new ControlPointsLayer(view.scene, () => view.invalidate());
  const presence = new PresenceLayer(view.scene, () => view.invalidate());
  const cageLayer = new CageLayer(view.scene, () => view.invalidate());
  // Which cage edges show depends on the camera: laid out before every frame.
  view.beforeRender = () => cageLayer.update((id) => vertices.lookup(id), view.camera.position.toArray());
  const start = new StartPanel(document.getElementById('start'));

  const page = new PageState({ ...presetNamed(params.lod ?? DEFAULT_PRESET) }, performance.now());
  page.decoder = decoder;
  decoder.ready.then(() => { page.milestones.decoderReady = Math.round(performance.now()); }, () => {});
  page.views = params.views;
  page.codec = params.codec;
  // Once the decoder has failed the page is stopped, and that stays the
  // error shown, not what stopping the connection makes fail after it.
  const showError = (text) => { if (!decoder.failure) page.lastError = text; };
  // The control cage (docs/WEB_VIEWER.md "The control cage"), of the
  // level the dots show.
  const cage = new CageControl({ layer: cageLayer, session: () => page.session, level: () => editor.level, onError: showError });

  const refreshMarkers = () => {
    controlPoints.setVertices(vertices.atLevel(editor.level));
    const others = page.session ? page.session.collaborators.list().filter((c) => c.sessionId !== page.session.sessionId) : [];
    presence.update(others, editor.picks, (id) => vertices.lookup(id)?.position ?? null);
    cage.sync();
  };

  const hud = new Hud(document.getElementById('hud'), {
    onPreset: (name) => {
      page.profile = { ...presetNamed(name) };
      page.session?.subscribeOrShallower(page.profile).catch((e) => showError(`subscribe: ${e.message}`));
    },
    // Another region codec: the same profile again, now in that codec
    // (docs/REGION_ENCODING.md "meshopt regions"); the server answers with
    // a snapshot in it.
    onCodec: (codec) => {
      page.codec = codec;
      if (!page.session) return;
      page.session.codec = codec;
      page.session.subscribeOrShallower(page.profile).catch((e) => showError(`subscribe: ${e.message}`));
    },
    onWireframe: (on) => view.setWireframe(on),
    onRegionColours: (on) => view.setRegionColours(on),
    onCage: (on) => cage.setOn(on),
    onLevel: (delta) => { editor.setLevel(editor.level + delta); refreshMarkers(); },
    // A new tolerance is a new view: sent like a camera move.
    onTolerance: (px) => { params.tolerance = px; offerView(); },
  });
  view.reservedTop = () => hud.coveredTop() + 8;

  const editor = new Editor({
    element: view.renderer.domElement, view, picker, vertices, controlPoints,
    session: () => page.session,
    maxLevel: () => page.profile.maxLevel,
    level: params.level ?? 1,
    onChange: refreshMarkers,
    onError: showError,
    toggleHud: () => hud.toggle(),
    toggleCage: () => cage.toggle(),
  });
  editor.clampLevel();
  cage.setOn(params.cage);

  // TESSERA_TEST_HOOK is replaced by build.mjs: true only in a test build
  // (--test-hook). Otherwise the branch, and with it test_hook.js, is left
  // out of the bundle.
  if (TESSERA_TEST_HOOK) installTestHook({ page, view, picker, vertices, editor, cage });

  function openDocument(documentId, helloAck) {
    page.session = new DocumentSession({
      connection: page.connection, documentId, profile: page.profile, codec: page.codec,
      // The first subscription: the coarsest tiles whatever the camera
      // (PROTOCOL.md section 16); the page frames them, then sends its own.
      view: page.views ? cameraView(256) : null,
      decode: (bytes) => page.decoder.decode(bytes),
      onView: (change) => {
        view.apply(change, page.session.view.regions);
        vertices.apply(change, page.session.view.regions);
        editor.refreshHover();
        refreshMarkers();
        if (change.kind === 'snapshot') page.readyAfterRender = true;
      },
      onPresence: refreshMarkers,
      onProfile: (p) => { page.profile = p; editor.clampLevel(); },
      // Before the first subscription: the page shows regions, and the
      // panel the LOD preset.
      onProfileOnly: () => { page.views = false; view.useTiles(false); },
      onStatus: (s) => { page.status = s; },
      onError: showError,
    });
    start.hide();
    page.session.connected(helloAck);
  }

  async function chooseDocument(helloAck) {
    try {
      const reply = await page.connection.call({ list_documents: {} });
      const documents = reply.message.document_list.documents.map((d) => ({
        id: toBig(d.document_id), name: d.name, version: toBig(d.version),
      }));
      if (params.documentId !== null) {
        page.documentName = documents.find((d) => d.id === params.documentId)?.name ?? '';
        return;
      }
      setBodyState('choosing');
      start.listDocuments(documents, (id) => {
        window.history.replaceState(null, '', addressWithDocument(window.location, id));
        params.documentId = id;
        page.documentName = documents.find((d) => d.id === id)?.name ?? '';
        openDocument(id, helloAck);
      });
    } catch (error) {
      showError(`list documents: ${error.message}`);
    }
  }

  function begin(token) {
    start.message('Connecting…');
    page.connection = new Connection({
      url: webSocketUrl(window.location), token, name: params.name, wire,
      createSocket: (url) => new WebSocket(url),
      onReady: (helloAck) => {
        page.milestones.helloAck ??= Math.round(performance.now());
        page.lastError = '';
        if (params.documentId !== null) {
          if (page.session) page.session.connected(helloAck); else openDocument(params.documentId, helloAck);
        }
        chooseDocument(helloAck);
      },
      onMessage: (body, message) => page.session?.message(body, message),
      onStatus: (s) => { page.status = s; },
      onError: (text, fatal) => {
        showError(text);
        if (page.connection?.permanentError) {
          setBodyState('error');
          start.askToken((t) => { setTokenInAddress(t); window.location.reload(); }, text);
        } else if (fatal) {
          page.status = 'the server closed the connection';
        }
      },
      onClosed: () => {
        page.ready = false;
        if (document.body.dataset.state === 'ready') setBodyState('connecting');
      },
    });
    setBodyState('connecting');
    page.connection.start();
  }

  // The render loop: an animation frame is asked for only when something
  // changed (view.invalidate(), the camera's controls), and a drawn frame
  // asks for the next while the camera still moves (damping). An idle page
  // asks for none: a page that asks at every frame keeps the browser's
  // compositor busy, which under a software renderer cost most of a core
  // for twenty idle tabs. The HUD is refreshed four times a second on a
  // timer (the DOM costs more than a frame of a small model); the frame
  // rate counts the frames drawn in each half second, 0 when idle.
  const askFrame = () => {
    if (page.frameAsked) return;
    page.frameAsked = true;
    requestAnimationFrame(frame);
  };
  const frame = () => {
    page.frameAsked = false;
    const drew = view.renderIfNeeded();
    if (!drew) return;
    offerView();
    ++page.fpsFrames;
    askFrame();
    if (page.session?.view.ready && page.session.view.version !== page.shownVersion) {
      page.shownVersion = page.session.view.version;
      page.shownAt.set(String(page.shownVersion), Date.now());
      if (page.shownAt.size > 4096) page.shownAt.delete(page.shownAt.keys().next().value);
    }
    if (page.readyAfterRender) {
      page.readyAfterRender = false;
      if (!page.firstPicture) {
        const shown = view.shownIds();
        const regions = page.session.view.regions;
        page.firstPicture = {
          ms: Math.round(performance.now()), triangles: view.triangles, shown: shown.map(String).sort(),
          bytes: shown.reduce((n, id) => n + (regions.get(id)?.bytes ?? 0), 0),
        };
      }
      page.ready = true;
      setBodyState('ready');
    }
  };
  view.onInvalidate = askFrame;
  askFrame();
  const hudTick = () => {
    const now = performance.now();
    if (now - page.fpsAt >= 500) {
      page.fps = (page.fpsFrames * 1000) / (now - page.fpsAt);
      page.fpsFrames = 0;
      page.fpsAt = now;
    }
    if (now - page.bytesSampleAt >= 1000 && page.connection) {
      page.bytesPerSecond = ((page.connection.bytesReceived - page.bytesAt) * 1000) / (now - page.bytesSampleAt);
      page.bytesAt = page.connection.bytesReceived;
      page.bytesSampleAt = now;
    }
    hud.update({
      fps: page.fps, triangles: view.triangles, regions: page.session?.view.regions.size ?? 0,
      version: page.session?.view.version ?? 0n, documentId: page.session?.documentId ?? null, documentName: page.documentName,
      role: page.session?.role ?? page.connection?.helloAck?.role ?? 0, latencyMs: page.session?.latency.last ?? null,
      bytesPerSecond: page.bytesPerSecond, hash: page.session?.lastHash ?? null, preset: page.profile.name?.split(' ')[0] ?? DEFAULT_PRESET,
      codec: page.codec,
      wireframe: view.wireframe, regionColours: view.regionColours, cage: cage.facts(), level: editor.level,
      views: page.views ? {
        complete: page.session?.viewComplete() ?? false, frozen: sender.frozen, tolerance: params.tolerance,
        preview: page.session?.view.regions.has(PREVIEW_ID) ?? false,
      } : null,
      pick: editor.describe(), points: controlPoints.count ?? 0, pointsDrawn: controlPoints.drawn,
      people: page.session ? page.session.collaborators.list().map((c) => ({ ...c, self: c.sessionId === page.session.sessionId })) : [],
      status: page.connection?.ready && page.session?.view.ready ? 'live' : page.status,
      error: page.lastError,
    });
  };
  setInterval(hudTick, HUD_INTERVAL_MS);

  // Nothing more can decode: stop rather than resubscribe for ever.
  function decodingFailed(error) {
    page.lastError = error.message;
    page.connection?.stop();
    setBodyState('error');
    start.message(`The region decoder did not load: ${error.message}`);
  }
  const connectUnlessFailed = (token) => { if (!decoder.failure) begin(token); };
  if (params.token) {
    connectUnlessFailed(params.token);
  } else {
    setBodyState('token');
    start.askToken((token) => {
      setTokenInAddress(token);
      connectUnlessFailed(token);
    });
  }
}

main();
