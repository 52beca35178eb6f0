// The draco3d decoder and encoder modules under Node, from node_modules:
// the same decoder the page runs, fed the same .wasm bytes.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { loadDraco } from '../../src/codec/draco.js';

const require = createRequire(import.meta.url);

export function dracoDecoder() {
  return loadDraco(readFileSync(require.resolve('draco3d/draco_decoder.wasm')));
}

export function dracoEncoder() {
  const createEncoderModule = require('draco3d/draco_encoder_nodejs.js');
  return createEncoderModule({ wasmBinary: readFileSync(require.resolve('draco3d/draco_encoder.wasm')) });
}
