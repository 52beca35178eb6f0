// The page's side of its decode workers (decode_worker.js; messages in
// decode_messages.js): decode(bytes) asks for one region payload and
// returns a Promise of the decoded region, or of the Error decodeRegion()
// threw, with the same message (docs/WEB_VIEWER.md "Decoding in a worker").
// The payloads asked for in one task go to a worker as one message, sent
// once the task ends. Answers may come in any order;
// session/ordered_updates.js applies them in the order the messages
// arrived.
//
// `ready` settles once every worker has its Draco module, or rejects with
// why one could not load it. A worker that stops (its script not served,
// an uncaught error) fails every request waiting and every later one, and
// onFailure(error) says so once: the page then stops rather than
// resubscribing forever to payloads nobody can decode.
const KEEP_SAMPLES = 4096;
const KEEP_BATCHES = 1024;

export class DecodePool {
  // options: {createWorker() -> a Worker, or a stand-in with postMessage,
  // onmessage and onerror; size: how many workers (requests go to the one
  // with the fewest waiting); onFailure(error)}.
  constructor({ createWorker, size = 1, onFailure = null }) {
    this.onFailure = onFailure;
    this.waiting = new Map(); // request id -> {resolve, reject, slot}
    this.nextId = 1;
    this.failure = null;
    this.decoded = 0; // regions the workers decoded
    this.decodedMeshopt = 0; // of which meshopt regions (docs/REGION_ENCODING.md "meshopt regions")
    this.failed = 0; // requests answered with an error
    this.totalMs = 0;
    this.samples = []; // the last KEEP_SAMPLES decode times, ms
    // The last KEEP_BATCHES answers of a worker, each the regions asked for
    // in one task (one WebSocket message: a snapshot part or a delta):
    // {regions, meshopt (of them), bytes (of their payloads), ms (the
    // worker's decode time, summed)}. The benchmark's decode time per delta
    // (bench/web_viewer_bench.mjs).
    this.batches = [];
    this.slots = [];
    this.flushAsked = false;
    const started = [];
    for (let i = 0; i < size; ++i) {
      const slot = { worker: createWorker(), outstanding: 0, batch: [], dracoLoaded: false, started: null };
      started.push(new Promise((resolve, reject) => { slot.started = { resolve, reject }; }));
      slot.worker.onmessage = (event) => this.received(slot, event.data);
      slot.worker.onerror = (event) => {
        event?.preventDefault?.();
        this.fail(new Error(`the decode worker stopped: ${event?.message || 'its script did not load'}`));
      };
      this.slots.push(slot);
    }
    this.ready = Promise.all(started);
    this.ready.catch(() => {}); // also reported by fail(); a caller may not wait
  }

  decode(bytes) {
    if (this.failure) return Promise.reject(this.failure);
    const slot = this.slots.reduce((a, b) => (b.outstanding < a.outstanding ? b : a));
    const id = this.nextId++;
    const copy = new Uint8Array(bytes); // its own buffer, exactly the payload's bytes
    ++slot.outstanding;
    slot.batch.push({ id, bytes: copy });
    if (!this.flushAsked) {
      this.flushAsked = true;
      queueMicrotask(() => this.flush());
    }
    return new Promise((resolve, reject) => {
      this.waiting.set(id, { resolve, reject, slot, bytes: copy.length });
    });
  }

  // Sends each worker what was asked of it in this task, as one message.
  flush() {
    this.flushAsked = false;
    for (const slot of this.slots) {
      const requests = slot.batch;
      slot.batch = [];
      if (requests.length === 0 || this.failure) continue; // failed: rejected already
      slot.worker.postMessage({ requests }, requests.map((r) => r.bytes.buffer));
    }
  }

  received(slot, data) {
    if (data.ready) {
      slot.dracoLoaded = Boolean(data.dracoLoaded);
      slot.started.resolve();
      return;
    }
    if (data.loadFailed !== undefined) {
      this.fail(new Error(data.loadFailed));
      return;
    }
    const batch = { regions: 0, meshopt: 0, bytes: 0, ms: 0 };
    for (const answer of data.answers ?? []) {
      const request = this.waiting.get(answer.id);
      if (request) {
        ++batch.regions;
        batch.bytes += request.bytes;
        batch.ms += answer.ms;
        if (answer.region?.header?.codec === 'meshopt') ++batch.meshopt;
      }
      this.answered(slot, answer);
    }
    if (batch.regions === 0) return;
    this.batches.push(batch);
    if (this.batches.length > KEEP_BATCHES) this.batches.shift();
  }

  answered(slot, data) {
    const request = this.waiting.get(data.id);
    if (!request) return; // failed already
    this.waiting.delete(data.id);
    --slot.outstanding;
    this.totalMs += data.ms;
    this.samples.push(data.ms);
    if (this.samples.length > KEEP_SAMPLES) this.samples.shift();
    if (data.error !== undefined) {
      ++this.failed;
      request.reject(new Error(data.error));
    } else {
      ++this.decoded;
      if (data.region?.header?.codec === 'meshopt') ++this.decodedMeshopt;
      request.resolve(data.region);
    }
  }

  fail(error) {
    if (this.failure) return;
    this.failure = error;
    for (const slot of this.slots) slot.started.reject(error);
    for (const request of this.waiting.values()) request.reject(error);
    this.waiting.clear();
    this.onFailure?.(error);
  }

  // For the panel and the test hook: {workers, decoded, decodedMeshopt,
  // failed, waiting, meanMs, p99Ms (of the last 4,096 decodes; null before any),
  // workerDraco (every worker has its module)}.
  facts() {
    const sorted = [...this.samples].sort((a, b) => a - b);
    const count = this.decoded + this.failed;
    return {
      workers: this.slots.length,
      decoded: this.decoded,
      decodedMeshopt: this.decodedMeshopt,
      failed: this.failed,
      waiting: this.waiting.size,
      meanMs: count ? this.totalMs / count : null,
      p99Ms: sorted.length ? sorted[Math.min(sorted.length - 1, Math.floor(0.99 * sorted.length))] : null,
      workerDraco: this.slots.every((s) => s.dracoLoaded),
    };
  }
}
