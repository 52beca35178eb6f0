// The schema's text, bundled by esbuild's text loader (build.mjs) and parsed
// at run time (wire.js), so the page speaks exactly the tree's
// protocol/tessera.proto with no generated code to keep in step.
export { default } from '../../../../protocol/tessera.proto';
