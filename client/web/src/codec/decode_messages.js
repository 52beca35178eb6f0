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
//                   returns it (its arrays transferred) and the decode's
//                   time, or {id, error: message, ms}, what decodeRegion()
//                   threw.
// Every request is answered once, with a region or an error.

// Set on the global object of the realm (the page's or a worker's) that
// created a Draco module (draco.js): how the test hook tells that the
// page's main thread never did.
export const DRACO_LOADED_MARK = 'tesseraDracoLoaded';

// The buffers of a decoded region, to transfer rather than copy; each array
// has a buffer of its own (region_decoder.js).
export function transferablesOf(region) {
  return [region.positions, region.normals, region.indices, region.idHi, region.idLo]
    .filter((a) => a !== null).map((a) => a.buffer);
}
