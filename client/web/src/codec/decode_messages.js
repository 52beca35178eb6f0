// What the page and its decode worker (decode_worker.js, decode_pool.js)
// say to each other (docs/WEB_VIEWER.md "Decoding in a worker"):
//
//   page -> worker  {requests: [{id, bytes}]}: region payloads, each a
//                   Uint8Array whose buffer is transferred (a copy of the
//                   payload alone: the WebSocket frame it came in holds
//                   other regions). The payloads asked for in one task (a
//                   snapshot's or a delta's) go as one message: a snapshot
//                   of 6,400 regions is one message each way, not 6,400.
//   worker -> page  {ready: true, dracoLoaded} once its Draco module is
//                   instantiated, or {loadFailed: message};
//                   {answers: [...]}, one per request of a message, in its
//                   order: {id, region, ms}, the region as decodeRegion()
//                   returns it and the decode's time, or {id, error:
//                   message, ms}, what decodeRegion() threw. The arrays of
//                   all its regions are views of one buffer, transferred
//                   (packAnswers()).
// Every request is answered once, with a region or an error.

// Set on the global object of the realm (the page's or a worker's) that
// created a Draco module (draco.js): how the test hook tells that the
// page's main thread never did.
export const DRACO_LOADED_MARK = 'tesseraDracoLoaded';

const ARRAYS = ['positions', 'normals', 'indices', 'idHi', 'idLo'];

// Moves the arrays of every decoded region among `answers` into one
// ArrayBuffer, each becoming a view of it, and returns the transfer list:
// that buffer. Transferring each array instead costs more than copying
// them when regions are small (6,400 regions of about 15 triangles: 360 ms
// for 32,000 transfers in one structuredClone under Node, 210 ms to copy,
// 120 ms packed; docs/WEB_VIEWER.md "Decoding in a worker"). Every array is
// of 4-byte elements, so every view is aligned.
export function packAnswers(answers) {
  let bytes = 0;
  for (const a of answers) for (const key of ARRAYS) bytes += a.region?.[key]?.byteLength ?? 0;
  if (bytes === 0) return [];
  const buffer = new ArrayBuffer(bytes);
  let at = 0;
  for (const a of answers) {
    for (const key of ARRAYS) {
      const array = a.region?.[key];
      if (!array) continue;
      const view = new array.constructor(buffer, at, array.length);
      view.set(array);
      a.region[key] = view;
      at += array.byteLength;
    }
  }
  return [buffer];
}
