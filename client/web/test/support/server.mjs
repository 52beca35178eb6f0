// A tessera-server of this tree's release build on 127.0.0.1 with an
// ephemeral port, a fresh data directory and an admin token, for the tests.
// Stopped by stop(); its log goes to the data directory.
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync, existsSync, openSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { randomBytes } from 'node:crypto';

export const SERVER_BINARY = process.env.TESSERA_SERVER ??
  new URL('../../../../build/release/server/tessera-server', import.meta.url).pathname;

// The build's extracted test data (CGAL's meshes under testdata/cgal): in
// the build directory whose server the tests run.
export const BUILD_DIR = process.env.TESSERA_BUILD_DIR ?? resolve(dirname(SERVER_BINARY), '..');
export const testData = (path) => join(BUILD_DIR, 'testdata', path);

export function serverAvailable() {
  return existsSync(SERVER_BINARY);
}

// Whether this build serves the WebSocket transport (--ws-port).
export function serverHasWebSocket() {
  if (!serverAvailable()) return false;
  const help = spawnSync(SERVER_BINARY, ['--help'], { encoding: 'utf8' });
  return /--ws-port/.test(help.stdout + help.stderr);
}

// `path` absolute, or relative to the server's data directory.
async function waitForFile(path, what, child) {
  for (let i = 0; i < 200; ++i) {
    if (existsSync(path) && readFileSync(path, 'utf8').trim() !== '') return readFileSync(path, 'utf8').trim();
    if (child.exitCode !== null) throw new Error(`tessera-server exited with ${child.exitCode} before writing ${what}`);
    await new Promise((r) => setTimeout(r, 50));
  }
  throw new Error(`tessera-server wrote no ${what} in 10 s`);
}

// options: extraArgs (e.g. ['--ws-port', '0', ...]); dir and port to start
// again on the data and port of a stopped server (with keep: true).
export async function startServer(options = {}) {
  const dir = options.dir ?? mkdtempSync(join(tmpdir(), 'tessera-web-test-'));
  const token = options.dir ? readFileSync(join(dir, 'admin.token'), 'utf8').trim() : randomBytes(24).toString('hex');
  if (!options.dir) writeFileSync(join(dir, 'admin.token'), token + '\n', { mode: 0o600 });
  const portFile = join(dir, 'port');
  rmSync(portFile, { force: true });
  const log = openSync(join(dir, 'server.log'), 'a');
  const args = ['--data', join(dir, 'store'), '--listen', '127.0.0.1', '--port', String(options.port ?? 0), '--port-file', portFile,
    '--admin-token-file', join(dir, 'admin.token'), '--network-threads', '1', ...(options.extraArgs ?? [])];
  const child = spawn(SERVER_BINARY, args, { stdio: ['ignore', log, log] });
  // A test that dies must not leave its server behind.
  const orphanGuard = () => child.kill('SIGKILL');
  process.once('exit', orphanGuard);
  const port = Number(await waitForFile(portFile, 'its port', child));
  return {
    dir,
    port,
    token,
    child,
    waitForFile: (name, what) => waitForFile(resolve(dir, name), what, child),
    async stop() {
      process.removeListener('exit', orphanGuard);
      if (child.exitCode === null) {
        child.kill('SIGTERM');
        await new Promise((r) => child.once('exit', r));
      }
      if (!options.keep) rmSync(dir, { recursive: true, force: true });
    },
  };
}
