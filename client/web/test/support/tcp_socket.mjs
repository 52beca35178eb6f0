// The server's TCP transport behind the WebSocket interface that
// connection.js uses (readyState, binaryType, onopen, onmessage with one
// frame per message, onclose, send, close), so the tests drive the page's
// own connection and document code against a real tessera-server before,
// or beside, its WebSocket port.
import net from 'node:net';
import { FrameSplitter } from '../../src/codec/wire.js';

export function tcpSocketFactory(port, host = '127.0.0.1') {
  return () => {
    const ws = { readyState: 0, binaryType: 'arraybuffer', onopen: null, onmessage: null, onclose: null, onerror: null };
    const splitter = new FrameSplitter();
    const socket = net.connect(port, host, () => {
      ws.readyState = 1;
      ws.onopen?.();
    });
    socket.on('data', (chunk) => {
      for (const frame of splitter.push(new Uint8Array(chunk))) {
        ws.onmessage?.({ data: frame.buffer.slice(frame.byteOffset, frame.byteOffset + frame.byteLength) });
      }
    });
    socket.on('error', () => ws.onerror?.());
    socket.on('close', () => {
      ws.readyState = 3;
      ws.onclose?.();
    });
    ws.send = (bytes) => socket.write(bytes);
    ws.close = () => socket.end();
    return ws;
  };
}
