// The link to the server over one WebSocket (docs/PROTOCOL.md 1, 4, 5):
// the Hello first, a client_seq per command, replies matched by client_seq
// (they can come out of order), a Ping every 30 s so that the idle timeout
// never closes a viewer that only listens, and reconnection with a backoff
// doubling from 0.5 s to 10 s. A refused token (ERROR_CODE_AUTH_FAILED), and
// handshakes no retry can fix, end the retrying: the page shows why.
//
// The socket is made by `createSocket(url)` so that the tests can put the
// TCP transport behind the same interface.
import { PROTOCOL_VERSION } from '../codec/wire.js';
import { toBig, toLong } from '../codec/uint64.js';

const PING_MS = 30000;
const FIRST_RETRY_MS = 500, LAST_RETRY_MS = 10000;

export class RejectError extends Error {
  constructor(reason, reasonName, message) {
    super(`${reasonName}: ${message}`);
    this.reason = reason;
    this.reasonName = reasonName;
  }
}

export class Connection {
  // options: {url, token, name, wire, createSocket, onReady(helloAck),
  // onMessage(body, message), onStatus(text), onError(text, fatal),
  // onClosed(wasReady), pingMs (default 30 s)}.
  constructor(options) {
    this.o = options;
    this.wire = options.wire;
    this.seq = 0;
    this.pending = new Map(); // client_seq -> {resolve, reject, sentAt}
    this.connected = false;
    this.ready = false;
    this.stopped = false; // no more retries
    this.retryMs = FIRST_RETRY_MS;
    this.bytesReceived = 0;
    this.frames = 0;
    this.reconnects = 0;
    this.pongs = 0;
    this.helloAck = null;
    this.permanentError = null;
  }

  start() {
    this.open();
  }

  stop() {
    this.stopped = true;
    clearInterval(this.pingTimer);
    clearTimeout(this.retryTimer);
    if (this.socket) this.socket.close();
  }

  open() {
    this.o.onStatus?.(this.reconnects ? 'reconnecting' : 'connecting');
    const socket = this.o.createSocket(this.o.url);
    this.socket = socket;
    socket.binaryType = 'arraybuffer';
    socket.onopen = () => {
      this.connected = true;
      this.retryMs = FIRST_RETRY_MS;
      this.seq = 0;
      this.o.onStatus?.('handshake');
      this.send({ hello: { protocol_version: PROTOCOL_VERSION, client_name: this.o.name, token: this.o.token } });
      this.pingTimer = setInterval(() => this.call({ ping: {} }).then(() => ++this.pongs, () => {}), this.o.pingMs ?? PING_MS);
    };
    socket.onmessage = (event) => this.receive(new Uint8Array(event.data));
    socket.onclose = () => this.closed(socket);
    socket.onerror = () => {}; // onclose follows and says what happens next
  }

  receive(bytes) {
    this.bytesReceived += bytes.length;
    ++this.frames;
    let message;
    try {
      message = this.wire.decodeServer(bytes);
    } catch (error) {
      this.o.onError?.(`a frame from the server does not decode: ${error.message}`, true);
      this.socket.close();
      return;
    }
    const body = this.wire.bodyOf(message);
    if (body === 'hello_ack') return this.helloAcked(message.hello_ack);
    if (body === 'error') return this.serverError(message.error);
    const reply = body && message[body].client_seq !== undefined ? this.pending.get(Number(toBig(message[body].client_seq))) : null;
    if (reply && body !== 'snapshot' && body !== 'delta' && body !== 'presence') {
      this.pending.delete(Number(toBig(message[body].client_seq)));
      if (body === 'reject') {
        const r = message.reject;
        reply.reject(new RejectError(r.reason, this.wire.names.RejectReason[r.reason] ?? `reason ${r.reason}`, r.message));
      } else {
        reply.resolve({ body, message, sentAt: reply.sentAt });
      }
      return;
    }
    if (body === 'reject') {
      // A reply nobody waits for, e.g. a refused Select.
      const r = message.reject;
      this.o.onError?.(`${this.wire.names.RejectReason[r.reason] ?? r.reason}: ${r.message}`, false);
      return;
    }
    if (body) this.o.onMessage?.(body, message);
  }

  helloAcked(ack) {
    if (ack.protocol_version !== PROTOCOL_VERSION) {
      this.permanent(`the server speaks protocol ${ack.protocol_version}, this viewer ${PROTOCOL_VERSION}`);
      return;
    }
    this.helloAck = ack;
    this.ready = true;
    this.o.onStatus?.('connected');
    this.o.onReady?.(ack);
  }

  serverError(error) {
    const name = this.wire.names.ErrorCode[error.code] ?? `ERROR_CODE ${error.code}`;
    const codes = this.wire.enums.ErrorCode;
    const hopeless = [codes.ERROR_CODE_AUTH_FAILED, codes.ERROR_CODE_VERSION_MISMATCH, codes.ERROR_CODE_BAD_HANDSHAKE];
    if (error.fatal && hopeless.includes(error.code)) {
      this.permanent(`${name}: ${error.message}`);
      return;
    }
    this.o.onError?.(`${name}: ${error.message}`, error.fatal);
  }

  permanent(text) {
    this.permanentError = text;
    this.stopped = true;
    this.o.onError?.(text, true);
    this.socket.close();
  }

  closed(socket) {
    if (socket !== this.socket) return;
    clearInterval(this.pingTimer);
    const wasReady = this.ready;
    this.connected = false;
    this.ready = false;
    for (const p of this.pending.values()) p.reject(new Error('the connection was lost before the answer came'));
    this.pending.clear();
    this.o.onClosed?.(wasReady);
    if (this.stopped) {
      this.o.onStatus?.(this.permanentError ? 'refused' : 'closed');
      return;
    }
    this.o.onStatus?.(`disconnected: retrying in ${(this.retryMs / 1000).toFixed(1)} s`);
    this.retryTimer = setTimeout(() => {
      ++this.reconnects;
      this.open();
    }, this.retryMs);
    this.retryMs = Math.min(this.retryMs * 2, LAST_RETRY_MS);
  }

  // Sends one command; returns its client_seq. Commands sent while the
  // socket is not open are dropped (they would reach no session).
  send(command) {
    const seq = ++this.seq;
    if (!this.socket || this.socket.readyState !== 1) throw new Error('not connected');
    this.socket.send(this.wire.encodeClient({ client_seq: toLong(seq), ...command }));
    return seq;
  }

  // Sends a command and resolves with its reply ({body, message, sentAt}),
  // or rejects with a RejectError or a lost connection.
  call(command) {
    return new Promise((resolve, reject) => {
      let seq;
      try {
        seq = this.send(command);
      } catch (error) {
        reject(error);
        return;
      }
      this.pending.set(seq, { resolve, reject, sentAt: performance.now() });
    });
  }
}
