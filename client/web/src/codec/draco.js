// The Draco WebAssembly decoder of the draco3d package. Its
// draco_decoder_nodejs.js is an Emscripten wrapper that runs in browsers and
// Node alike; the page hands it the .wasm bytes fetched from the server
// (build.mjs copies draco_decoder.wasm beside viewer.js), the tests read them
// from node_modules. One module per realm, created on first use: in the
// page, the decode worker's (decode_worker.js).
import createDecoderModule from 'draco3d/draco_decoder_nodejs.js';
import { DRACO_LOADED_MARK } from './decode_messages.js';

let loading = null;

// wasmBinary: an ArrayBuffer or Uint8Array of draco_decoder.wasm.
export function loadDraco(wasmBinary) {
  if (!loading) {
    globalThis[DRACO_LOADED_MARK] = true; // this realm has a Draco module
    loading = new Promise((resolve, reject) => {
      createDecoderModule({ wasmBinary }).then(resolve, reject);
    });
  }
  return loading;
}

// The page's way: fetch the .wasm next to the page, then instantiate.
export async function loadDracoFrom(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`the Draco decoder ${url}: HTTP ${response.status}`);
  const bytes = new Uint8Array(await response.arrayBuffer());
  return { draco: await loadDraco(bytes), bytes: bytes.length };
}
