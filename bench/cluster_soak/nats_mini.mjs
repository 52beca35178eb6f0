// A minimal NATS client (the text protocol over TCP, no dependency) for the
// soak's driver and checker: requests to JetStream's API only, to read the
// journal stream and the lease bucket straight from the NATS servers,
// without a Tessera node in between.
import net from 'node:net';

export class MiniNats {
  static connect(port, timeoutMs = 3000) {
    return new Promise((resolve, reject) => {
      const c = new MiniNats();
      const timer = setTimeout(() => { c.close(); reject(new Error(`NATS 127.0.0.1:${port}: no INFO in ${timeoutMs} ms`)); }, timeoutMs);
      c.socket = net.connect(port, '127.0.0.1');
      c.socket.on('error', (e) => { clearTimeout(timer); c.fail(e); reject(e); });
      c.socket.on('close', () => c.fail(new Error('NATS connection closed')));
      c.onInfo = () => {
        clearTimeout(timer);
        c.socket.write('CONNECT {"verbose":false,"pedantic":false,"headers":true,"no_responders":true,"name":"soak"}\r\nSUB _INBOX.soak.* 1\r\n');
        resolve(c);
      };
      c.socket.on('data', (d) => c.data(d));
    });
  }

  constructor() {
    this.buf = Buffer.alloc(0);
    this.next = 0;
    this.waiting = new Map(); // inbox -> {resolve, reject, timer}
    this.closed = false;
  }

  fail(error) {
    for (const w of this.waiting.values()) { clearTimeout(w.timer); w.reject(error); }
    this.waiting.clear();
  }

  close() {
    this.closed = true;
    this.socket?.destroy();
  }

  data(chunk) {
    this.buf = Buffer.concat([this.buf, chunk]);
    for (;;) {
      const eol = this.buf.indexOf('\r\n');
      if (eol < 0) return;
      const line = this.buf.subarray(0, eol).toString();
      if (line.startsWith('MSG ') || line.startsWith('HMSG ')) {
        const parts = line.split(' ');
        const headers = parts[0] === 'HMSG';
        const total = Number(parts[parts.length - 1]);
        const headerBytes = headers ? Number(parts[parts.length - 2]) : 0;
        if (this.buf.length < eol + 2 + total + 2) return;
        const body = this.buf.subarray(eol + 2, eol + 2 + total);
        this.buf = this.buf.subarray(eol + 2 + total + 2);
        this.message(parts[1], body.subarray(0, headerBytes).toString(), Buffer.from(body.subarray(headerBytes)));
        continue;
      }
      this.buf = this.buf.subarray(eol + 2);
      if (line.startsWith('INFO')) this.onInfo?.();
      else if (line === 'PING') this.socket.write('PONG\r\n');
    }
  }

  message(subject, headers, body) {
    const w = this.waiting.get(subject);
    if (!w) return;
    this.waiting.delete(subject);
    clearTimeout(w.timer);
    if (/^NATS\/1.0 503/.test(headers)) w.reject(new Error('no responders'));
    else w.resolve(body);
  }

  request(subject, payload = '', timeoutMs = 3000) {
    return new Promise((resolve, reject) => {
      if (this.closed) return reject(new Error('closed'));
      const inbox = `_INBOX.soak.${++this.next}`;
      const timer = setTimeout(() => { this.waiting.delete(inbox); reject(new Error(`${subject}: no answer in ${timeoutMs} ms`)); }, timeoutMs);
      this.waiting.set(inbox, { resolve, reject, timer });
      const bytes = Buffer.from(payload);
      this.socket.write(`PUB ${subject} ${inbox} ${bytes.length}\r\n`);
      this.socket.write(bytes);
      this.socket.write('\r\n');
    });
  }

  async json(subject, payload = '', timeoutMs = 3000) {
    return JSON.parse((await this.request(subject, typeof payload === 'string' ? payload : JSON.stringify(payload), timeoutMs)).toString());
  }
}

// The document's lease holder per TESSERA_LEASES (docs/CLUSTER.md), or null.
export async function leaseOwner(nats, documentId) {
  const r = await nats.json('$JS.API.STREAM.MSG.GET.KV_TESSERA_LEASES', { last_by_subj: `$KV.TESSERA_LEASES.doc.${documentId}` }, 1500);
  if (!r.message) return null;
  const hdrs = r.message.hdrs ? Buffer.from(r.message.hdrs, 'base64').toString() : '';
  if (/KV-Operation:\s*(DEL|PURGE)/i.test(hdrs)) return null;
  return Buffer.from(r.message.data ?? '', 'base64').toString();
}

// Every message of `stream` whose subject is `subject`, in stream order:
// {seq, subject, data (Buffer)}. Asks for each sequence (32 at a time).
export async function readStream(nats, stream, subject) {
  const info = await nats.json(`$JS.API.STREAM.INFO.${stream}`, '', 10000);
  if (info.error) throw new Error(`${stream}: ${JSON.stringify(info.error)}`);
  const first = info.state.first_seq, last = info.state.last_seq;
  const out = [];
  for (let s = first; s <= last; s += 32) {
    const batch = [];
    for (let q = s; q <= Math.min(last, s + 31); ++q) {
      batch.push(nats.json(`$JS.API.STREAM.MSG.GET.${stream}`, { seq: q }, 10000).then((r) => ({ q, r })));
    }
    for (const { q, r } of await Promise.all(batch)) {
      if (!r.message) continue; // deleted or not found
      if (subject && r.message.subject !== subject) continue;
      out.push({ seq: q, subject: r.message.subject, data: Buffer.from(r.message.data ?? '', 'base64') });
    }
  }
  return { messages: out, state: info.state };
}

// docs/CLUSTER.md, server/cluster/journal_message.h:
// "TJ2" | kind u8 | version u64 LE | author length u32 LE | author | session u64 LE | client_seq u64 LE | bytes
export function decodeJournalMessage(data) {
  if (data.subarray(0, 3).toString() !== 'TJ2') return { bad: `no TJ2 header (${data.length} bytes)` };
  let o = 3;
  const kind = data.readUInt8(o); o += 1;
  const version = data.readBigUInt64LE(o); o += 8;
  const n = data.readUInt32LE(o); o += 4;
  const author = data.subarray(o, o + n).toString(); o += n;
  const session = data.readBigUInt64LE(o); o += 8;
  const clientSeq = data.readBigUInt64LE(o); o += 8;
  return { fence: kind === 1, kind, version: version.toString(), author, session: session.toString(), clientSeq: clientSeq.toString(), entryBytes: data.length - o, entry: data.subarray(o).toString('base64') };
}
