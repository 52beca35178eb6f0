// The wire: tessera.wire messages (protocol/tessera.proto, parsed at run
// time by protobufjs, encoded and decoded by proto_codec.js) in the frames
// of docs/PROTOCOL.md 2. Over the WebSocket transport each binary message
// carries exactly one frame, its 4-byte big-endian length prefix included,
// so one message is prefix + payload and the prefix equals the message's
// length - 4.
//
// Field names stay as the schema spells them (keepCase), so code reads like
// PROTOCOL.md: msg.snapshot.remaining_parts. uint64 fields decode as
// unsigned long.js Longs; uint64.js turns them into BigInts.
import protobuf from 'protobufjs';
import Long from 'long';
import { encodeMessage, decodeMessage } from './proto_codec.js';

// protobufjs looks for long.js itself; a bundle must hand it over, or 64-bit
// fields would decode as lossy numbers.
protobuf.util.Long = Long;
protobuf.configure();

export const PROTOCOL_VERSION = 1;
const PREFIX_BYTES = 4;

export function createWire(protoText) {
  const root = protobuf.parse(protoText, { keepCase: true }).root;
  root.resolveAll();
  const ClientMessage = root.lookupType('tessera.wire.ClientMessage');
  const ServerMessage = root.lookupType('tessera.wire.ServerMessage');
  const enums = {
    Role: root.lookupEnum('tessera.wire.Role').values,
    RejectReason: root.lookupEnum('tessera.wire.RejectReason').values,
    ErrorCode: root.lookupEnum('tessera.wire.ErrorCode').values,
    MoveMode: root.lookupEnum('tessera.wire.MoveMode').values,
    VertexType: root.lookupEnum('tessera.wire.VertexType').values,
  };
  // Value -> name, for messages people read ("REJECT_REASON_NOT_FOUND").
  const names = {};
  for (const [enumName, values] of Object.entries(enums)) {
    names[enumName] = Object.fromEntries(Object.entries(values).map(([k, v]) => [v, k]));
  }

  function frame(Type, fields) {
    const payload = encodeMessage(Type, fields);
    const out = new Uint8Array(PREFIX_BYTES + payload.length);
    new DataView(out.buffer).setUint32(0, payload.length, false);
    out.set(payload, PREFIX_BYTES);
    return out;
  }

  function unframe(Type, bytes) {
    if (bytes.length < PREFIX_BYTES) throw new Error(`a frame of ${bytes.length} bytes has no length prefix`);
    const length = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength).getUint32(0, false);
    if (length === 0) throw new Error('a frame announces 0 bytes');
    if (length !== bytes.length - PREFIX_BYTES) {
      throw new Error(`a frame announces ${length} bytes but carries ${bytes.length - PREFIX_BYTES}`);
    }
    return decodeMessage(Type, bytes.subarray(PREFIX_BYTES));
  }

  return {
    root,
    enums,
    names,
    // One ClientMessage as one WebSocket message (prefix included).
    encodeClient: (fields) => frame(ClientMessage, fields),
    decodeServer: (bytes) => unframe(ServerMessage, bytes),
    // The other direction, for tests that play the server.
    encodeServer: (fields) => frame(ServerMessage, fields),
    decodeClient: (bytes) => unframe(ClientMessage, bytes),
    bodyOf: (serverMessage) => serverMessage.body,
    commandOf: (clientMessage) => clientMessage.command,
  };
}

// Splits a byte stream (the TCP transport, used by the tests) into frames,
// each returned with its prefix as one WebSocket message would carry it.
export class FrameSplitter {
  constructor() {
    this.pending = new Uint8Array(0);
  }

  push(chunk) {
    const joined = new Uint8Array(this.pending.length + chunk.length);
    joined.set(this.pending);
    joined.set(chunk, this.pending.length);
    const frames = [];
    let at = 0;
    while (joined.length - at >= PREFIX_BYTES) {
      const length = new DataView(joined.buffer, at, PREFIX_BYTES).getUint32(0, false);
      if (joined.length - at < PREFIX_BYTES + length) break;
      frames.push(joined.slice(at, at + PREFIX_BYTES + length));
      at += PREFIX_BYTES + length;
    }
    this.pending = joined.slice(at);
    return frames;
  }
}
