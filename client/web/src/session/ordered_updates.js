// Snapshots and deltas applied one at a time, in the order they arrived,
// while their region payloads decode elsewhere (the page's Web Worker,
// codec/decode_pool.js) and may finish in any order (docs/WEB_VIEWER.md
// "Decoding in a worker").
//
//   - push() starts decoding every payload of a message at once and queues
//     the message behind those that came before it.
//   - The message at the head is asked, against the view as it is then,
//     whether its regions will be read (DocumentView.needsRegions). If not
//     (a delta after a gap, before the snapshot that ends it; another
//     document's message) it is applied at once, its decodes left to finish
//     unread: the view ignores it, as it would have without decoding it.
//     Otherwise it waits for its own decodes, never for a later message's.
//   - A decode that fails is a settled {error}, not a rejection: apply()
//     throws it where a synchronous decoder would have (DocumentView), so
//     a bad payload is a gap and a resubscription, never a drop or a hang.
//   - reset() (a new connection, with a new view) drops everything queued:
//     those results belong to a subscription that no longer exists.
//
// With a synchronous decoder and nothing queued a message is applied within
// push(), as before there was a worker (the Node tests' sessions).
export class OrderedUpdates {
  // options: {decode(bytes) -> a decoded region, or a Promise of one (it may
  // throw or reject), payloads(body, message) -> its Uint8Arrays in order,
  // needsRegions(body, message) -> bool, apply(body, message, decoded) with
  // decoded one {region} or {error} per payload, or null when not needed}.
  constructor(options) {
    this.o = options;
    this.queue = []; // {body, message, results: [{region} | {error} | Promise of one]}
    this.draining = false;
    this.epoch = 0; // bumped by reset(): a wait that spans it is stale
    this.applied = 0;
    this.dropped = 0;
  }

  // Messages waiting for their turn or their decodes.
  get pending() {
    return this.queue.length;
  }

  push(body, message) {
    const results = this.o.payloads(body, message).map((bytes) => settle(this.o.decode, bytes));
    const entry = { body, message, results };
    if (!this.draining && this.queue.length === 0 && !results.some(isPromise)) {
      this.applyEntry(entry, results);
      return;
    }
    this.queue.push(entry);
    this.drain();
  }

  reset() {
    this.dropped += this.queue.length;
    this.queue = [];
    ++this.epoch;
  }

  async drain() {
    if (this.draining) return;
    this.draining = true;
    try {
      while (this.queue.length > 0) {
        const entry = this.queue[0];
        let decoded = null;
        if (this.o.needsRegions(entry.body, entry.message)) {
          const epoch = this.epoch;
          decoded = await Promise.all(entry.results);
          if (epoch !== this.epoch) continue; // reset meanwhile: the queue is another
        }
        this.queue.shift();
        try {
          this.applyEntry(entry, decoded);
        } catch (error) {
          // Uncaught, as it would be in a synchronous apply, without
          // stalling the messages behind it.
          queueMicrotask(() => { throw error; });
        }
      }
    } finally {
      this.draining = false;
    }
  }

  applyEntry(entry, decoded) {
    ++this.applied;
    this.o.apply(entry.body, entry.message, decoded);
  }
}

function isPromise(value) {
  return typeof value?.then === 'function';
}

// {region} or {error}, or a Promise of one that never rejects.
function settle(decode, bytes) {
  let out;
  try {
    out = decode(bytes);
  } catch (error) {
    return { error };
  }
  return isPromise(out) ? out.then((region) => ({ region }), (error) => ({ error })) : { region: out };
}
