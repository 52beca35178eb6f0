// The cluster soak's driver (docs/CLUSTER.md "Fault-injection soak"): three
// nats-server processes (JetStream, clustered) and three tessera-server nodes
// on loopback, each node reaching its NATS servers through TCP proxies of
// this process (so that one node can be cut off from NATS while its clients
// stay connected), an editor and a viewer per node, and a seeded random
// schedule of faults. Everything each client sent and got is logged to
// files in the run directory; check.mjs judges them afterwards.
//
//   node driver.mjs --dir DIR --bin BINDIR --repo REPO [--faults N] [--duration S] [--seed S] [--base-port P]
import { spawn, spawnSync } from 'node:child_process';
import { mkdirSync, openSync, writeFileSync, appendFileSync, readFileSync, existsSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import net from 'node:net';
import { MiniNats, leaseOwner, readStream, decodeJournalMessage } from './nats_mini.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((acc, a, i, all) => {
  if (a.startsWith('--')) acc.push([a.slice(2), all[i + 1]]);
  return acc;
}, []));
const DIR = args.dir, BIN = args.bin, REPO = args.repo;
const DURATION = Number(args.duration ?? 1800);
const SEED = Number(args.seed ?? 1);
const BASE = Number(args['base-port'] ?? 25100);
const LEASE_MS = Number(args['lease-ms'] ?? 2000);
const EDIT_RATE = Number(args['edit-rate'] ?? 4); // commands per second per editor
const MAX_OUTSTANDING = 3;

const webRoot = new URL(`file://${REPO}/client/web/`);
const { createWire, FrameSplitter } = await import(new URL('src/codec/wire.js', webRoot));
const { Connection } = await import(new URL('src/session/connection.js', webRoot));
const { DocumentSession } = await import(new URL('src/session/document_session.js', webRoot));
const { decodeRegion } = await import(new URL('src/codec/region_decoder.js', webRoot));
const { toBig, toLong, hex64 } = await import(new URL('src/codec/uint64.js', webRoot));
const { dracoDecoder } = await import(new URL('test/support/draco_node.mjs', webRoot));
const wire = createWire(readFileSync(join(REPO, 'protocol/tessera.proto'), 'utf8'));
const draco = await dracoDecoder();
const PROFILE = { baseLevel: 2, maxLevel: 5, angle: 10 }; // tessera-replay surface's default (2,5,10)

// mulberry32: the schedule is a function of SEED alone.
function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6D2B79F5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
const scheduleRandom = rng(SEED);
const clientRandom = rng(SEED ^ 0x9e3779b9); // the edits' choices: not part of the schedule
const t0 = Date.now();
const now = () => (Date.now() - t0) / 1000;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const log = (file, record) => appendFileSync(join(DIR, file), JSON.stringify({ t: Number(now().toFixed(3)), ...record }) + '\n');
const event = (what, detail = {}) => {
  log('events.jsonl', { what, ...detail });
  console.log(`[${now().toFixed(1).padStart(7)} s] ${what} ${JSON.stringify(detail)}`);
};

// ---- processes ----------------------------------------------------------
const natsClient = (i) => BASE + 1 + i;   // 3 NATS client ports
const natsRoute = (i) => BASE + 11 + i;   // 3 route ports
const nodePort = (n) => BASE + 21 + n;    // 3 tessera nodes
const proxyPort = (n, i) => BASE + 31 + 3 * n + i; // node n -> NATS i
const children = new Set();

function startProcess(name, command, argv) {
  const out = openSync(join(DIR, `${name}.log`), 'a');
  const child = spawn(command, argv, { stdio: ['ignore', out, out], detached: true });
  child.soakName = name;
  children.add(child);
  child.on('exit', () => children.delete(child));
  return child;
}
// Like spawnSync, without blocking this process's event loop (the proxies
// and the clients live in it).
function run(command, argv, timeoutMs) {
  return new Promise((resolve) => {
    const child = spawn(command, argv, { stdio: ['ignore', 'pipe', 'pipe'], detached: true });
    children.add(child);
    let stdout = '', stderr = '';
    child.stdout.on('data', (d) => { stdout += d; });
    child.stderr.on('data', (d) => { stderr += d; });
    const timer = setTimeout(() => killGroup(child), timeoutMs);
    child.on('exit', (status) => { clearTimeout(timer); children.delete(child); resolve({ status, stdout, stderr }); });
  });
}
function killGroup(child, signal = 'SIGKILL') {
  try { process.kill(-child.pid, signal); } catch { /* gone */ }
}
function killAll() {
  for (const c of children) { killGroup(c, 'SIGCONT'); killGroup(c, 'SIGKILL'); }
}
process.on('exit', killAll);
for (const s of ['SIGINT', 'SIGTERM']) process.on(s, () => { killAll(); process.exit(130); });

const nats = [null, null, null];
function startNats(i) {
  const conf = join(DIR, `nats${i}.conf`);
  if (!existsSync(conf)) {
    writeFileSync(conf, `server_name: nats${i}
listen: 127.0.0.1:${natsClient(i)}
max_payload: 8MB
jetstream { store_dir: "${join(DIR, `nats${i}`)}", max_mem: 256MB, max_file: 2GB }
cluster {
  name: soak
  no_advertise: true
  listen: 127.0.0.1:${natsRoute(i)}
  routes: [${[0, 1, 2].map((j) => `nats://127.0.0.1:${natsRoute(j)}`).join(', ')}]
}
`);
  }
  nats[i] = startProcess(`nats${i}`, 'nats-server', ['-c', conf]);
}

const nodes = [null, null, null];
const nodeState = ['down', 'down', 'down']; // up | stopped | down
function startNode(n) {
  const urls = [0, 1, 2].map((i) => `nats://127.0.0.1:${proxyPort(n, i)}`).join(',');
  nodes[n] = startProcess(`node${n}`, join(BIN, 'tessera-server'), ['--cluster', urls, '--node-name', `node${n}`,
    '--listen', '127.0.0.1', '--port', String(nodePort(n)), '--lease-ms', String(LEASE_MS), '--network-threads', '1']);
  nodeState[n] = 'up';
}

// ---- the proxies between each node and its NATS servers -----------------
// mode 'pass' forwards; 'drop' resets every connection and every new one;
// 'blackhole' keeps connections open and forwards nothing either way (new
// ones are accepted and held), until healed: then the held connections are
// reset, as a TCP connection that timed out would be, and new ones pass.
const proxies = [0, 1, 2].map((n) => ({ node: n, mode: 'pass', pairs: new Set(), servers: [] }));
function startProxies() {
  for (const p of proxies) {
    for (let i = 0; i < 3; ++i) {
      const server = net.createServer((client) => {
        if (p.mode === 'drop') { client.destroy(); return; }
        const upstream = net.connect(natsClient(i), '127.0.0.1');
        const pair = { client, upstream };
        p.pairs.add(pair);
        const end = () => { client.destroy(); upstream.destroy(); p.pairs.delete(pair); };
        client.on('data', (d) => { if (p.mode === 'pass' && !pair.held) upstream.write(d); });
        upstream.on('data', (d) => { if (p.mode === 'pass' && !pair.held) client.write(d); });
        if (p.mode === 'blackhole') pair.held = true;
        client.on('error', end); upstream.on('error', end); client.on('close', end); upstream.on('close', end);
      });
      server.listen(proxyPort(p.node, i), '127.0.0.1');
      p.servers.push(server);
    }
  }
}
function partition(n, mode) {
  const p = proxies[n];
  p.mode = mode;
  for (const pair of [...p.pairs]) {
    if (mode === 'drop') { pair.client.destroy(); pair.upstream.destroy(); p.pairs.delete(pair); }
    else pair.held = true;
  }
}
function heal(n) {
  const p = proxies[n];
  p.mode = 'pass';
  for (const pair of [...p.pairs]) if (pair.held) { pair.client.destroy(); pair.upstream.destroy(); p.pairs.delete(pair); }
}

// ---- editors --------------------------------------------------------------
// One connection at a time; every command sent and its outcome are logged:
// send, ack (version, edit id), reject (reason, message), lost (the
// connection closed before an answer), notice (a server Error: the pending
// commands at that moment are named), dup (a second answer to a seq).
class Editor {
  constructor(index, documentId) {
    this.index = index;
    this.name = `editor${index}`;
    this.file = `${this.name}.jsonl`;
    this.documentId = documentId;
    this.node = index;
    this.stopped = false;
    this.sent = 0;
  }
  log(record) { log(this.file, record); }
  connect() {
    if (this.stopped) return;
    const node = this.node;
    const socket = net.connect(nodePort(node), '127.0.0.1');
    const s = { socket, node, seq: 0, session: null, ready: false, pending: new Map(), answered: new Map(), closed: false };
    this.s = s;
    const splitter = new FrameSplitter();
    const send = (fields) => {
      const seq = ++s.seq;
      socket.write(wire.encodeClient({ client_seq: toLong(seq), ...fields }));
      return seq;
    };
    s.send = send;
    socket.on('connect', () => send({ hello: { protocol_version: 1, client_name: this.name, token: TOKEN } }));
    socket.on('data', (chunk) => {
      for (const frame of splitter.push(new Uint8Array(chunk))) {
        let m;
        try { m = wire.decodeServer(frame); } catch (e) { this.log({ kind: 'bad-frame', error: e.message }); socket.destroy(); return; }
        this.receive(s, wire.bodyOf(m), m);
      }
    });
    const closed = () => {
      if (s.closed) return;
      s.closed = true;
      if (s.session !== null || s.pending.size) {
        this.log({ kind: 'closed', node, session: s.session, pending: [...s.pending.keys()] });
      }
      for (const seq of s.pending.keys()) this.log({ kind: 'lost', node, session: s.session, seq, why: 'connection closed before an answer' });
      s.pending.clear();
      if (this.stopped) return;
      // Reconnect, to the next node when this one refused or died.
      if (!s.ready || s.moveAway) this.node = (this.node + 1 + Math.floor(clientRandom() * 2)) % 3;
      setTimeout(() => this.connect(), 200 + Math.floor(clientRandom() * 800));
    };
    socket.on('error', closed);
    socket.on('close', closed);
  }
  receive(s, body, m) {
    if (body === 'hello_ack') {
      s.session = toBig(m.hello_ack.session_id).toString();
      this.log({ kind: 'session', node: s.node, session: s.session });
      s.openSeq = s.send({ open_document: { document_id: toLong(this.documentId) } });
      return;
    }
    if (body === 'error') {
      this.log({ kind: 'notice', node: s.node, session: s.session, code: wire.names.ErrorCode[m.error.code], fatal: m.error.fatal,
        message: m.error.message, pending: [...s.pending.keys()] });
      return;
    }
    const seq = m[body]?.client_seq !== undefined ? Number(toBig(m[body].client_seq)) : null;
    if (seq === s.openSeq && (body === 'ack' || body === 'reject')) {
      if (body === 'ack') s.ready = true;
      else this.log({ kind: 'open-refused', node: s.node, session: s.session, message: m.reject.message });
      if (!s.ready) { s.moveAway = true; s.socket.destroy(); }
      return;
    }
    if (body !== 'ack' && body !== 'reject') return;
    const outcome = body === 'ack'
      ? { kind: 'ack', version: toBig(m.ack.version).toString(), edit: toBig(m.ack.edit_id).toString() }
      : { kind: 'reject', reason: wire.names.RejectReason[m.reject.reason], message: m.reject.message };
    if (s.pending.has(seq)) {
      const sent = s.pending.get(seq);
      s.pending.delete(seq);
      s.answered.set(seq, outcome);
      this.log({ ...outcome, node: s.node, session: s.session, seq, ms: Date.now() - sent });
    } else {
      this.log({ ...outcome, kind: `dup-${outcome.kind}`, node: s.node, session: s.session, seq, first: s.answered.get(seq) ?? null });
    }
  }
  tick() {
    const s = this.s;
    if (this.stopped || !s || !s.ready || s.closed || s.pending.size >= MAX_OUTSTANDING) return;
    const vertex = Math.floor(clientRandom() * 8); // v0:0 .. v0:7 of the cube
    const d = () => Number(((clientRandom() - 0.5) * 0.02).toFixed(6));
    const target = { x: d(), y: d(), z: d() };
    const seq = s.send({ move_vertex: { document_id: toLong(this.documentId), vertex_ids: [toLong(BigInt(vertex))], target, mode: 2 } });
    s.pending.set(seq, Date.now());
    ++this.sent;
    this.log({ kind: 'send', node: s.node, session: s.session, seq, vertex, target });
  }
  moveAway() {
    if (!this.s || this.s.closed) return false;
    this.s.moveAway = true;
    this.s.socket.destroy();
    return true;
  }
}

// ---- viewers: the web client's own Connection and DocumentSession ----------
class Viewer {
  constructor(index, documentId) {
    this.index = index;
    this.name = `viewer${index}`;
    this.file = `${this.name}.jsonl`;
    this.node = index;
    this.versions = 0;
    this.session = null;
    const self = this;
    this.connection = new Connection({
      url: 'tcp', token: TOKEN, name: this.name, wire,
      createSocket: () => self.socket(),
      onReady: (ack) => { log(self.file, { kind: 'session', node: self.connectedNode, session: toBig(ack.session_id).toString() }); self.session.connected(ack); },
      onMessage: (body, m) => self.session.message(body, m),
      onError: (text, fatal) => log(self.file, { kind: 'error', node: self.connectedNode, text, fatal: Boolean(fatal) }),
      onClosed: (wasReady) => { if (!wasReady) self.moveNext = true; log(self.file, { kind: 'closed', node: self.connectedNode, wasReady }); },
      pingMs: 5000,
    });
    this.session = new DocumentSession({
      connection: this.connection, documentId, profile: PROFILE, decode: (bytes) => decodeRegion(draco, bytes),
      onView: (change) => {
        ++self.versions;
        if (change.kind === 'snapshot') log(self.file, { kind: 'snapshot', version: self.session.view.version.toString(), hash: hex64(self.session.view.surfaceHash()) });
      },
      onError: (text) => log(self.file, { kind: 'session-error', node: self.connectedNode, text }),
    });
  }
  socket() {
    if (this.moveNext) { this.node = (this.node + 1) % 3; this.moveNext = false; }
    this.connectedNode = this.node;
    return TCP.tcpSocketFactory(nodePort(this.node))();
  }
  start() { this.connection.start(); }
  moveAway() {
    this.moveNext = true;
    this.connection.socket?.close();
    return true;
  }
  stop() { this.connection.stop(); }
}
const TCP = await import(new URL('test/support/tcp_socket.mjs', webRoot));

// ---- the faults -------------------------------------------------------------
async function owner() {
  for (const i of [0, 1, 2]) {
    if (!nats[i] || nats[i].exitCode !== null) continue;
    try {
      const c = await MiniNats.connect(natsClient(i), 1000);
      try { const o = await leaseOwner(c, DOC); if (o !== null) return o; } finally { c.close(); }
    } catch { /* next */ }
  }
  return null;
}
const counts = {};
const count = (k) => { counts[k] = (counts[k] ?? 0) + 1; };
const pick = (list) => list[Math.floor(scheduleRandom() * list.length)];
const between = (lo, hi) => lo + scheduleRandom() * (hi - lo);

const KINDS = [
  ['kill-owner', 3], ['kill-other-node', 2], ['pause-within-lease', 2], ['pause-past-lease', 2],
  ['kill-one-nats', 2], ['kill-all-nats', 1], ['client-moves', 2], ['partition-node', 3],
];
// --kinds a,b: only these kinds (equal weights), to try one kind of fault.
if (args.kinds) {
  const only = args.kinds.split(',');
  for (const k of only) if (!KINDS.some(([name]) => name === k)) { console.error(`unknown fault kind ${k}`); process.exit(2); }
  KINDS.splice(0, KINDS.length, ...only.map((k) => [k, 1]));
}
// --every-kind N: each kind N times, in an order drawn from SEED, and no
// other fault (the bounded run CI makes: FAULTS is N times the number of
// kinds).
const everyKindTimes = args['every-kind'] === undefined ? 0 : Number(args['every-kind']);
if (args['every-kind'] !== undefined && !(Number.isInteger(everyKindTimes) && everyKindTimes >= 1 && everyKindTimes <= 50)) {
  console.error(`--every-kind must be a whole number of times from 1 to 50, not "${args['every-kind']}"`);
  process.exit(2);
}
const everyKindOrder = everyKindTimes ? Array.from({ length: everyKindTimes }, () => KINDS.map(([k]) => k)).flat() : null;
if (everyKindOrder) {
  for (let i = everyKindOrder.length - 1; i > 0; --i) {
    const j = Math.floor(scheduleRandom() * (i + 1));
    [everyKindOrder[i], everyKindOrder[j]] = [everyKindOrder[j], everyKindOrder[i]];
  }
}
const FAULTS = everyKindOrder ? everyKindOrder.length : Number(args.faults ?? 200);
function chooseKind(number) {
  if (everyKindOrder) return everyKindOrder[number - 1];
  const total = KINDS.reduce((s, [, w]) => s + w, 0);
  let r = scheduleRandom() * total;
  for (const [k, w] of KINDS) { if ((r -= w) < 0) return k; }
  return KINDS[0][0];
}

async function fault(number) {
  const kind = chooseKind(number);
  // Every random choice of the fault is drawn now, before anything is
  // observed, so that the schedule is the same for a seed whatever happens.
  const p = { a: scheduleRandom(), b: scheduleRandom(), c: scheduleRandom(), node: Math.floor(scheduleRandom() * 3) };
  count(kind);
  if (kind === 'kill-owner' || kind === 'kill-other-node') {
    let target = p.node;
    const o = await owner();
    const ownerIndex = o && /^node\d$/.test(o) ? Number(o.slice(4)) : null;
    if (kind === 'kill-owner' && ownerIndex !== null) target = ownerIndex;
    if (kind === 'kill-other-node' && ownerIndex !== null && target === ownerIndex) target = (target + 1 + Math.floor(p.c * 2)) % 3;
    const down = 200 + p.a * 4000;
    event('fault', { n: number, kind, node: `node${target}`, owner: o, restart_after_ms: Math.round(down) });
    killGroup(nodes[target]); nodeState[target] = 'down';
    await sleep(down);
    startNode(target);
    event('heal', { n: number, kind, node: `node${target}`, action: 'restarted' });
  } else if (kind === 'pause-within-lease' || kind === 'pause-past-lease') {
    const ms = kind === 'pause-within-lease' ? 100 + p.a * (LEASE_MS * 0.5) : LEASE_MS * (1.5 + p.a * 2.5);
    const o = await owner();
    const target = p.b < 0.6 && o && /^node\d$/.test(o) ? Number(o.slice(4)) : p.node;
    event('fault', { n: number, kind, node: `node${target}`, owner: o, pause_ms: Math.round(ms) });
    killGroup(nodes[target], 'SIGSTOP'); nodeState[target] = 'stopped';
    await sleep(ms);
    killGroup(nodes[target], 'SIGCONT'); nodeState[target] = 'up';
    event('heal', { n: number, kind, node: `node${target}`, action: 'SIGCONT' });
  } else if (kind === 'kill-one-nats') {
    const i = p.node, down = 500 + p.a * 7500;
    event('fault', { n: number, kind, nats: `nats${i}`, restart_after_ms: Math.round(down) });
    killGroup(nats[i]);
    await sleep(down);
    startNats(i);
    event('heal', { n: number, kind, nats: `nats${i}`, action: 'restarted' });
  } else if (kind === 'kill-all-nats') {
    const down = 500 + p.a * 4500;
    event('fault', { n: number, kind, restart_after_ms: Math.round(down) });
    for (const i of [0, 1, 2]) killGroup(nats[i]);
    await sleep(down);
    for (const i of [0, 1, 2]) startNats(i);
    event('heal', { n: number, kind, action: 'restarted all three' });
  } else if (kind === 'client-moves') {
    const who = p.b < 0.5 ? editors[p.node] : viewers[p.node];
    event('fault', { n: number, kind, client: who.name, from: `node${who.node}` });
    who.moveAway();
  } else if (kind === 'partition-node') {
    const mode = p.b < 0.5 ? 'blackhole' : 'drop';
    const ms = 1000 + p.a * (LEASE_MS * 5);
    const o = await owner();
    const target = p.c < 0.5 && o && /^node\d$/.test(o) ? Number(o.slice(4)) : p.node;
    event('fault', { n: number, kind, mode, node: `node${target}`, owner: o, ms: Math.round(ms) });
    partition(target, mode);
    await sleep(ms);
    heal(target);
    event('heal', { n: number, kind, node: `node${target}`, action: 'proxy passes again' });
  }
}

// ---- the run -----------------------------------------------------------------
async function portFree(port) {
  return new Promise((r) => {
    const s = net.createServer();
    s.once('error', () => r(false));
    s.listen(port, '127.0.0.1', () => s.close(() => r(true)));
  });
}
for (const port of [0, 1, 2].flatMap((i) => [natsClient(i), natsRoute(i), nodePort(i), proxyPort(i, 0), proxyPort(i, 1), proxyPort(i, 2)])) {
  if (!(await portFree(port))) { console.error(`port ${port} is taken: choose another BASE_PORT`); process.exit(2); }
}
mkdirSync(DIR, { recursive: true });
event('start', { seed: SEED, faults: FAULTS, duration_s: DURATION, base_port: BASE, lease_ms: LEASE_MS, edit_rate: EDIT_RATE });
for (const i of [0, 1, 2]) startNats(i);
startProxies();
const directUrls = [0, 1, 2].map((i) => `nats://127.0.0.1:${natsClient(i)}`).join(',');
let TOKEN = null;
for (let attempt = 0; attempt < 60 && !TOKEN; ++attempt) {
  const r = await run(join(BIN, 'tessera-server'), ['token', 'new', '--role', 'admin', '--cluster', directUrls], 20000);
  if (r.status === 0 && r.stdout.trim()) TOKEN = r.stdout.trim().split('\n').pop().trim();
  else await sleep(500);
}
if (!TOKEN) { console.error('no token: JetStream did not come up'); process.exit(1); }
writeFileSync(join(DIR, 'admin.token'), TOKEN + '\n', { mode: 0o600 });
for (const n of [0, 1, 2]) startNode(n);
for (const n of [0, 1, 2]) {
  let ok = false;
  for (let i = 0; i < 200 && !ok; ++i) { ok = !(await portFree(nodePort(n))); if (!ok) await sleep(100); }
  if (!ok) { console.error(`node${n} did not listen; see ${DIR}/node${n}.log`); process.exit(1); }
}
let DOC = 0, create = null;
for (let attempt = 0; attempt < 30 && !DOC; ++attempt) {
  create = await run(join(BIN, 'tessera'), ['remote', 'create', join(REPO, 'tests/data/cube.obj'), '--tags', join(REPO, 'tests/data/cube.tags'),
    '--max-level', '5', '--port', String(nodePort(0)), '--token-file', join(DIR, 'admin.token')], 60000);
  DOC = create.status === 0 ? Number(create.stdout.trim()) : 0;
  if (!DOC) await sleep(1000);
}
if (!DOC) { console.error(`create failed: ${create.stdout} ${create.stderr}`); process.exit(1); }
event('document', { id: DOC });

const editors = [0, 1, 2].map((i) => new Editor(i, DOC));
const viewers = [0, 1, 2].map((i) => new Viewer(i, DOC));
for (const e of editors) e.connect();
for (const v of viewers) v.start();
const editTimer = setInterval(() => { for (const e of editors) e.tick(); }, Math.round(1000 / EDIT_RATE));

// Every 5 s, the state of the journal and blob streams as one NATS server
// answers it (the next server each time), logged to streams.jsonl when it
// changes: the long run lost every message of TESSERA_BLOBS, and this says
// when. Never more than one question at a time.
let streamWatchBusy = false, lastStreams = '';
const streamWatch = setInterval(async () => {
  if (streamWatchBusy) return;
  streamWatchBusy = true;
  const i = Math.floor(Date.now() / 5000) % 3;
  try {
    const c = await MiniNats.connect(natsClient(i), 1000);
    try {
      const out = {};
      for (const name of ['TESSERA_JOURNAL', 'TESSERA_BLOBS']) {
        const info = await c.json(`$JS.API.STREAM.INFO.${name}`, '', 2000);
        out[name] = info.state ? { messages: info.state.messages, first: info.state.first_seq, last: info.state.last_seq, leader: info.cluster?.leader } : { error: info.error?.description };
      }
      const key = JSON.stringify(out.TESSERA_BLOBS) + (out.TESSERA_JOURNAL.error ?? '');
      if (key !== lastStreams) { lastStreams = key; log('streams.jsonl', { asked: `nats${i}`, ...out }); }
    } finally { c.close(); }
  } catch { /* that server is down or slow: the next one asks next time */ }
  streamWatchBusy = false;
}, 5000);

const slot = (DURATION * 1000) / FAULTS;
const runStart = Date.now();
for (let n = 1; n <= FAULTS; ++n) {
  const due = runStart + slot * (n - 1) + slot * 0.3 + scheduleRandom() * slot * 0.4;
  if (due > Date.now()) await sleep(due - Date.now());
  if (Date.now() - runStart > DURATION * 1000 * 1.5) { event('schedule-cut', { at_fault: n, why: 'past 1.5 x DURATION' }); break; }
  await fault(n);
}
const remaining = runStart + DURATION * 1000 - Date.now();
if (remaining > 0) await sleep(remaining);

// ---- the end: heal, stop editing, let answers arrive, then look --------------
event('healing', {});
for (const n of [0, 1, 2]) { heal(n); if (nodeState[n] === 'stopped') killGroup(nodes[n], 'SIGCONT'); if (!nodes[n] || nodes[n].exitCode !== null) startNode(n); }
for (const i of [0, 1, 2]) if (!nats[i] || nats[i].exitCode !== null) startNats(i);
clearInterval(editTimer);
clearInterval(streamWatch);
const drainUntil = Date.now() + 60000;
while (Date.now() < drainUntil && editors.some((e) => e.s && !e.s.closed && e.s.pending.size > 0)) await sleep(250);
event('drained', { pending: editors.map((e) => (e.s && !e.s.closed ? e.s.pending.size : 0)) });
for (const e of editors) {
  e.stopped = true;
  if (e.s && !e.s.closed) for (const seq of e.s.pending.keys()) e.log({ kind: 'unanswered-at-end', node: e.s.node, session: e.s.session, seq });
}

// Fresh subscribers, one per node, with the viewers' profile.
async function fresh(n) {
  const errors = [];
  let session;
  const connection = new Connection({
    url: 'tcp', token: TOKEN, name: `fresh${n}`, wire, createSocket: TCP.tcpSocketFactory(nodePort(n)),
    onReady: (ack) => session.connected(ack), onMessage: (b, m) => session.message(b, m), onError: (t) => errors.push(t),
  });
  session = new DocumentSession({ connection, documentId: DOC, profile: PROFILE, decode: (bytes) => decodeRegion(draco, bytes), onError: (t) => errors.push(t) });
  connection.start();
  const until = Date.now() + 15000;
  while (Date.now() < until && !session.view.ready) await sleep(50);
  const r = session.view.ready
    ? { node: n, version: session.view.version.toString(), hash: hex64(session.view.surfaceHash()), announced: hex64(session.view.announcedHash), errors }
    : { node: n, version: null, errors };
  connection.stop();
  return r;
}
const final = { seed: SEED, doc: DOC, counts, fresh: [], replaySurface: [], viewers: [], editors: [] };
// A fresh subscriber's version must hold still for 3 s: edits have stopped.
// Bounded: a document no node can load must not hold the run for long.
for (let i = 0; i < 4; ++i) {
  const a = await fresh(0);
  await sleep(3000);
  const b = await fresh(0);
  if (a.version && a.version === b.version) break;
}
for (const n of [0, 1, 2]) final.fresh.push(await fresh(n));
for (const n of [0, 1, 2]) {
  const r = await run(join(BIN, 'tessera-replay'), ['surface', '--port', String(nodePort(n)), '--token-file', join(DIR, 'admin.token'),
    '--document', String(DOC)], 30000);
  final.replaySurface.push({ node: n, status: r.status, out: (r.stdout + r.stderr).trim() });
}
const target = final.fresh.find((f) => f.version)?.version;
const viewUntil = Date.now() + 30000;
while (Date.now() < viewUntil && viewers.some((v) => !v.session.view.ready || v.session.view.version.toString() !== target)) await sleep(100);
for (const v of viewers) {
  const view = v.session.view;
  final.viewers.push({ name: v.name, node: v.connectedNode, ready: view.ready, version: view.version?.toString(), hash: view.ready ? hex64(view.surfaceHash()) : null,
    announced: view.ready ? hex64(view.announcedHash) : null, hashChecks: v.session.hashChecks, hashMismatches: v.session.hashMismatches,
    reconnects: v.connection.reconnects, updates: v.versions });
  v.stop();
}
for (const e of editors) final.editors.push({ name: e.name, sent: e.sent });

// The journal, straight from JetStream.
let journal = null;
for (let attempt = 0; attempt < 10 && !journal; ++attempt) {
  try {
    const c = await MiniNats.connect(natsClient(attempt % 3), 2000);
    try {
      const { messages, state } = await readStream(c, 'TESSERA_JOURNAL', `tessera.journal.${DOC}`);
      journal = messages.map((m) => ({ seq: m.seq, ...decodeJournalMessage(m.data) }));
      final.journalStream = state;
    } finally { c.close(); }
  } catch (e) { event('journal-read-failed', { error: e.message }); await sleep(2000); }
}
try {
  const c = await MiniNats.connect(natsClient(0), 2000);
  try {
    const infos = {};
    for (const name of ['TESSERA_JOURNAL', 'TESSERA_BLOBS']) infos[name] = await c.json(`$JS.API.STREAM.INFO.${name}`, '', 5000);
    // The base's manifest (docs/CLUSTER.md "What is stored where").
    const base = await c.json('$JS.API.STREAM.MSG.GET.TESSERA_BLOBS', { last_by_subj: `tessera.blob.${DOC}.base` }, 5000);
    final.baseManifest = base.message ? { seq: base.message.seq, time: base.message.time } : { missing: base.error?.description ?? 'no message' };
    writeFileSync(join(DIR, 'streams-at-end.json'), JSON.stringify(infos, null, 2));
  } finally { c.close(); }
} catch (e) { event('stream-info-failed', { error: e.message }); }
writeFileSync(join(DIR, 'journal.jsonl'), (journal ?? []).map((j) => JSON.stringify(j)).join('\n') + '\n');
final.journalRead = journal !== null;
final.elapsed_s = now();
writeFileSync(join(DIR, 'final.json'), JSON.stringify(final, null, 2));
event('done', { counts });
killAll();
for (const p of proxies) for (const s of p.servers) s.close();
// A bounded run that lost part of its schedule (past 1.5 x DURATION) did not
// test what it was asked to: say so rather than pass on fewer faults.
if (everyKindOrder) {
  const short = KINDS.filter(([k]) => (counts[k] ?? 0) !== everyKindTimes).map(([k]) => `${k} ${counts[k] ?? 0} times`);
  if (short.length) {
    console.error(`each kind of fault was to happen ${everyKindTimes} times, but the schedule was cut: ${short.join(', ')}`);
    process.exit(1);
  }
}
process.exit(0);
