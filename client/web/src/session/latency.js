// Edit-to-delta latency (docs/VIEWER.md): the time from sending an edit to
// the arrival of the delta that brings its version. An Ack names the
// version the edit made; a delta covers from_version < v <= to_version (a
// merged delta spans several). The delta can arrive before the Ack
// (6.1: merging can move it ahead), so arrivals of this session's own
// deltas are remembered too.
const KEEP = 256;

export class LatencyTracker {
  constructor(now = () => performance.now()) {
    this.now = now;
    this.waiting = new Map(); // acked version (BigInt) -> sent at
    this.arrivals = []; // {from, to, at} of deltas authored here, newest last
    this.last = null; // ms
    this.samples = 0;
  }

  // An edit's Ack: `version` it made, `sentAt` when the edit went out;
  // `viewVersion` is the version the view already shows.
  acked(version, sentAt, viewVersion) {
    if (version <= viewVersion) {
      const arrival = this.arrivals.find((a) => a.from < version && version <= a.to);
      if (arrival) this.record(arrival.at - sentAt);
      return;
    }
    this.waiting.set(version, sentAt);
    if (this.waiting.size > KEEP) this.waiting.delete(this.waiting.keys().next().value);
  }

  // A delta applied to the view; `own` when this session authored it.
  delta(from, to, own) {
    const at = this.now();
    for (const [version, sentAt] of this.waiting) {
      if (from < version && version <= to) {
        this.record(at - sentAt);
        this.waiting.delete(version);
      }
    }
    if (own) {
      this.arrivals.push({ from, to, at });
      if (this.arrivals.length > KEEP) this.arrivals.shift();
    }
  }

  record(ms) {
    this.last = ms;
    ++this.samples;
  }

  // After a reconnection nothing in flight will be answered.
  reset() {
    this.waiting.clear();
    this.arrivals = [];
  }
}
