// What the page's tests in Chromium start from: the page built fresh with
// its test hook (build.mjs --test-hook) into a temporary folder, served by a
// real tessera-server from its own --ws-port, and an admin session on the
// server's TCP port. stop() ends the session and the server and removes the
// build.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { startServer } from './server.mjs';
import { connect } from './client.mjs';

export async function startPageServer() {
  const web = mkdtempSync(join(tmpdir(), 'tessera-web-build-'));
  const portFile = `${web}.ws-port`;
  let server, admin;
  const stop = async () => {
    admin?.stop();
    await server?.stop();
    rmSync(web, { recursive: true, force: true });
    rmSync(portFile, { force: true });
  };
  try {
    const built = spawnSync(process.execPath, [new URL('../../build.mjs', import.meta.url).pathname, '--out', web, '--test-hook'],
      { encoding: 'utf8' });
    assert.equal(built.status, 0, built.stderr);
    server = await startServer({ extraArgs: ['--ws-port', '0', '--ws-port-file', portFile, '--web-root', web] });
    const base = `http://127.0.0.1:${await server.waitForFile(portFile, 'its web port')}`;
    admin = await connect(server.port, server.token, 'admin');
    return { server, admin, base, buildLog: built.stdout.trim(), stop };
  } catch (error) {
    await stop();
    throw error;
  }
}
