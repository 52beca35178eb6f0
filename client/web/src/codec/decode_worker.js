// The decode worker: bundled by build.mjs as decode_worker.js, the page
// starts it (codec/decode_pool.js). It instantiates the Draco module and the
// meshoptimizer decoder here, off the page's main thread, and decodes each
// region payload it is sent with decodeRegion(): header, checksum, Draco or
// meshopt (docs/REGION_ENCODING.md "meshopt regions"), ids and lattice ids,
// exactly as the page did before (docs/WEB_VIEWER.md "Decoding in a worker"). The
// arrays of a message's regions go back in one transferred buffer; an error
// goes back as its message.
// Messages: decode_messages.js.
import { loadDracoFrom } from './draco.js';
import { loadMeshopt } from './meshopt_region.js';
import { decodeRegion } from './region_decoder.js';
import { DRACO_LOADED_MARK, packAnswers } from './decode_messages.js';

// Beside this file, as build.mjs writes them.
const loaded = Promise.all([loadDracoFrom(new URL('draco_decoder.wasm', self.location.href).href), loadMeshopt()])
  .then(([dracoLoaded, meshopt]) => ({ ...dracoLoaded, meshopt }));
loaded.then(
  () => self.postMessage({ ready: true, dracoLoaded: globalThis[DRACO_LOADED_MARK] === true }),
  (error) => self.postMessage({ loadFailed: error?.message ?? String(error) }));

function answer(draco, meshopt, { id, bytes }) {
  const started = performance.now();
  try {
    return { id, region: decodeRegion(draco, bytes, meshopt), ms: performance.now() - started };
  } catch (error) {
    return { id, error: error?.message ?? String(error), ms: performance.now() - started };
  }
}

// Messages are answered in the order they came (each waits on the same
// promise); the page does not rely on it (session/ordered_updates.js).
self.onmessage = (event) => {
  const { requests } = event.data;
  loaded.then(({ draco, meshopt }) => {
    const answers = requests.map((request) => answer(draco, meshopt, request));
    self.postMessage({ answers }, packAnswers(answers));
  }, (error) => {
    const message = `the Draco or meshopt decoder did not load: ${error?.message ?? String(error)}`;
    self.postMessage({ answers: requests.map(({ id }) => ({ id, error: message, ms: 0 })) });
  });
};
