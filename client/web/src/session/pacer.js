// A token bucket in front of the connection: at most `rate` commands a
// second, in bursts of `burst`. The server refuses commands beyond its own
// bucket (200 a second by default, docs/PROTOCOL.md 5), and undoing a long
// drag sends one Undo per edit, so this viewer stays below it as
// tessera-view does (150 a second).
export class Pacer {
  constructor(rate = 150, burst = 150, now = () => performance.now()) {
    this.rate = rate;
    this.burst = burst;
    this.now = now;
    this.tokens = burst;
    this.at = now();
    this.queue = [];
    this.timer = null;
  }

  // Runs job() now if the bucket allows, later otherwise, in order. A job
  // may carry job.drop(), called instead if it is cleared away.
  run(job) {
    this.queue.push(job);
    this.drain();
  }

  drain() {
    const t = this.now();
    this.tokens = Math.min(this.burst, this.tokens + ((t - this.at) / 1000) * this.rate);
    this.at = t;
    while (this.queue.length > 0 && this.tokens >= 1) {
      this.tokens -= 1;
      this.queue.shift()();
    }
    if (this.queue.length > 0 && this.timer === null) {
      this.timer = setTimeout(() => {
        this.timer = null;
        this.drain();
      }, Math.ceil(((1 - this.tokens) / this.rate) * 1000));
    }
  }

  // Jobs not run yet are dropped (the connection they were for is gone).
  clear() {
    const dropped = this.queue;
    this.queue = [];
    for (const job of dropped) job.drop?.();
  }
}
