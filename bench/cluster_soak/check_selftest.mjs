// The checker must be able to fail: takes a run directory the checker
// passed (with its offline.json: offline_replay.py), and for each kind of damage copies its logs, damages the copy the
// way a bug would, and expects check.mjs to exit 1 naming that finding.
//
//   node bench/cluster_soak/check_selftest.mjs RUN_DIR
import { mkdtempSync, cpSync, readFileSync, writeFileSync, rmSync, readdirSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { tmpdir } from 'node:os';

const run = process.argv[2];
const checker = new URL('check.mjs', import.meta.url).pathname;
const logs = readdirSync(run).filter((f) => /\.(jsonl|json)$/.test(f) && f !== 'summary.json');
const read = (d, f) => readFileSync(join(d, f), 'utf8').split('\n').filter(Boolean).map((l) => JSON.parse(l));
const write = (d, f, rows) => writeFileSync(join(d, f), rows.map((r) => JSON.stringify(r)).join('\n') + '\n');
const entries = (rows) => rows.filter((r) => !r.fence && !r.bad);

const damages = [
  ['an acknowledged edit is not in the journal', (d) => {
    const j = read(d, 'journal.jsonl');
    const last = j.findLastIndex((r) => !r.fence);
    j.splice(last, 1); // the newest entry is gone, as if JetStream lost it
    write(d, 'journal.jsonl', j);
  }],
  ['a journal version appears twice (or goes back)', (d) => {
    const j = read(d, 'journal.jsonl');
    const e = entries(j)[5];
    j.splice(j.indexOf(e) + 1, 0, { ...e, seq: e.seq + 0.5, session: '1', clientSeq: '1' });
    write(d, 'journal.jsonl', j);
  }],
  ['one command is in the journal more than once', (d) => {
    const j = read(d, 'journal.jsonl');
    const es = entries(j);
    const last = es[es.length - 1];
    j.push({ ...es[3], seq: last.seq + 1, version: String(Number(last.version) + 1) });
    write(d, 'journal.jsonl', j);
  }],
  ['a command acknowledged twice with different versions', (d) => {
    const e = read(d, 'editor0.jsonl');
    const ack = e.find((r) => r.kind === 'ack');
    e.push({ ...ack, kind: 'dup-ack', version: String(Number(ack.version) + 1) });
    write(d, 'editor0.jsonl', e);
  }],
  ['a refused command is in the journal', (d) => {
    const e = read(d, 'editor1.jsonl');
    const i = e.findIndex((r) => r.kind === 'ack');
    e[i] = { t: e[i].t, kind: 'reject', reason: 'REJECT_REASON_NOT_FOUND', message: 'damaged', node: e[i].node, session: e[i].session, seq: e[i].seq };
    write(d, 'editor1.jsonl', e);
  }],
  ['a command got no answer and its author was not told it may be lost', (d) => {
    const e = read(d, 'editor2.jsonl');
    const i = e.findLastIndex((r) => r.kind === 'ack');
    e[i] = { t: e[i].t, kind: 'unanswered-at-end', node: e[i].node, session: e[i].session, seq: e[i].seq };
    write(d, 'editor2.jsonl', e);
  }],
  ['a journal entry no editor sent', (d) => {
    const j = read(d, 'journal.jsonl');
    const es = entries(j);
    const last = es[es.length - 1];
    j.push({ ...last, seq: last.seq + 1, version: String(Number(last.version) + 1), session: '99', clientSeq: '99' });
    write(d, 'journal.jsonl', j);
  }],
  ['a viewer did not converge to what a fresh subscriber sees', (d) => {
    const f = JSON.parse(readFileSync(join(d, 'final.json'), 'utf8'));
    f.viewers[1].hash = '0x0000000000000001';
    writeFileSync(join(d, 'final.json'), JSON.stringify(f));
  }],
  ['the document\'s base is missing from TESSERA_BLOBS at the end', (d) => {
    const f = JSON.parse(readFileSync(join(d, 'final.json'), 'utf8'));
    f.baseManifest = { missing: 'no message found' };
    writeFileSync(join(d, 'final.json'), JSON.stringify(f));
  }],
  ['the journal replayed offline differs from what the cluster serves', (d) => {
    const o = JSON.parse(readFileSync(join(d, 'offline.json'), 'utf8'));
    o.replayed.hash = '0x0000000000000002';
    writeFileSync(join(d, 'offline.json'), JSON.stringify(o));
  }],
];

// The undamaged copy first: it must pass, or the damages prove nothing.
let failures = 0;
for (const [expected, damage] of [['(none)', null], ...damages]) {
  const d = mkdtempSync(join(tmpdir(), 'tessera-soak-selftest-'));
  for (const f of logs) cpSync(join(run, f), join(d, f));
  if (damage) damage(d);
  const r = spawnSync('node', [checker, d], { encoding: 'utf8' });
  const summary = JSON.parse(readFileSync(join(d, 'summary.json'), 'utf8'));
  const ok = damage ? r.status === 1 && summary.findingKinds[expected] > 0 : r.status === 0;
  if (!ok) ++failures;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${damage ? `damage -> "${expected}"` : 'undamaged copy passes'} (exit ${r.status}; found ${JSON.stringify(summary.findingKinds)})`);
  rmSync(d, { recursive: true, force: true });
}
process.exit(failures ? 1 : 0);
