// The page's state, in one place: what main.js wires together and changes,
// and what the HUD and the test hook read. Plain fields; main.js is the only
// writer.
export class PageState {
  // profile: the LOD profile to subscribe with first; now: performance.now().
  constructor(profile, now) {
    // The link and the document.
    this.connection = null; // Connection, once a token is known
    this.session = null; // DocumentSession, once a document is chosen
    this.decoder = null; // the DecodePool: region payloads decode in a Web Worker
    this.profile = profile; // the LOD profile asked for (or stepped down to)
    // Whether the page subscribes with a view (tiles for its camera) rather
    // than the profile: the address's choice, off for a morph document.
    this.views = false;
    this.documentName = '';
    // The region codec subscribed with, 'draco' or 'meshopt': ?codec= at
    // first, then the panel's choice (docs/REGION_ENCODING.md "meshopt regions").
    this.codec = 'draco';

    // What the panel says.
    this.status = 'starting';
    this.lastError = '';

    // Readiness: the first snapshot is applied (readyAfterRender) and then
    // drawn (ready, and <body data-state=ready>).
    this.readyAfterRender = false;
    this.ready = false;
    // The first picture drawn: when (ms since the page started), its
    // triangles, the ids of the regions it draws (decimal strings) and their
    // payloads' bytes; with a view, the surface's preview or the coarsest
    // tiles, refined after.
    this.firstPicture = null;
    // On the way to it (ms since the page started, null until reached): the
    // decode worker's Draco module loaded, and the server's HelloAck.
    this.milestones = { decoderReady: null, helloAck: null };

    // When each version was first drawn (Unix ms, Date.now()): the
    // benchmark times edit-to-pixels against the editor's clock with it
    // (bench/web_viewer_bench.mjs). The last 4,096 versions.
    this.shownAt = new Map();
    this.shownVersion = -1n;

    // The render loop: whether an animation frame is asked for.
    this.frameAsked = false;

    // The panel's rates: frames drawn per second, sampled every half
    // second, and bytes received per second, sampled every second.
    this.fps = 0;
    this.fpsFrames = 0;
    this.fpsAt = now;
    this.bytesAt = 0;
    this.bytesSampleAt = now;
    this.bytesPerSecond = 0;
  }
}
