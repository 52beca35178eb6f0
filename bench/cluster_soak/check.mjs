// The cluster soak's checker (docs/CLUSTER.md "Fault-injection soak"): reads
// a run directory written by driver.mjs (the editors' logs, the viewers'
// logs, the journal as read from JetStream, the final looks) and checks
//   1. the journal: its entries' versions run 1, 2, 3, ... in stream order,
//      no version twice, every message decodes, fences never claim more;
//   2. every acknowledged edit is in the journal exactly once, at the
//      version of its Ack (journal version = Ack version - 1: the document is
//      at version 1 when created), from its author's session and client_seq;
//   3. no command is acknowledged twice with different versions, nor both
//      acknowledged and refused; no refused command is in the journal;
//   4. every command got an answer, or its author was told it may be lost
//      (its connection closed, or the server's notice named it as pending);
//   5. every journal entry is a command an editor sent;
//   6. every viewer ends at the version and surface hash fresh subscribers
//      see on every node (the web client's own assembly and hash, and
//      tessera-replay's surface), which is the journal's last version; no
//      viewer ever saw a surface hash that differs from the server's;
//      The document's base must still be in TESSERA_BLOBS at the end.
//   7. with offline.json (offline_replay.py): the journal replayed offline
//      by a single-node server from the same base gives that same version
//      and surface hash, and its base the cluster's hash at version 1.
// It also measures, per kind of fault, how long after the fault was healed
// the first edit was acknowledged again (any editor).
// Prints a summary, writes summary.json, exits 1 on any finding.
import { readFileSync, writeFileSync, readdirSync, existsSync } from 'node:fs';
import { join } from 'node:path';

const dir = process.argv[2];
const lines = (f) => (existsSync(join(dir, f)) ? readFileSync(join(dir, f), 'utf8').split('\n').filter(Boolean).map((l) => JSON.parse(l)) : []);
const findings = [];
const finding = (what, detail) => { if (findings.length < 2000) findings.push({ what, ...detail }); };

const final = JSON.parse(readFileSync(join(dir, 'final.json'), 'utf8'));
const events = lines('events.jsonl');
const journal = lines('journal.jsonl');
const files = readdirSync(dir);
const editorNames = files.filter((f) => /^editor\d+\.jsonl$/.test(f)).map((f) => f.replace('.jsonl', '')).sort();
const viewerNames = files.filter((f) => /^viewer\d+\.jsonl$/.test(f)).map((f) => f.replace('.jsonl', '')).sort();

// 1. The journal.
if (!final.journalRead) finding('the journal could not be read from JetStream', {});
const entries = [];
let fences = 0, lastVersion = 0;
for (const m of journal) {
  if (m.bad) { finding('a journal message does not decode', { seq: m.seq, bad: m.bad }); continue; }
  if (m.fence) {
    ++fences;
    if (Number(m.version) > lastVersion) finding('a fence claims a version beyond the entries before it', { seq: m.seq, version: m.version, last: lastVersion });
    continue;
  }
  const v = Number(m.version);
  if (v !== lastVersion + 1) finding(v <= lastVersion ? 'a journal version appears twice (or goes back)' : 'a gap in the journal\'s versions', { seq: m.seq, version: v, previous: lastVersion });
  lastVersion = Math.max(lastVersion, v);
  entries.push(m);
}
const byCommand = new Map(); // "session/seq" -> [entries]
for (const e of entries) {
  const k = `${e.session}/${e.clientSeq}`;
  if (!byCommand.has(k)) byCommand.set(k, []);
  byCommand.get(k).push(e);
}
for (const [k, list] of byCommand) {
  if (list.length > 1) finding('one command is in the journal more than once', { command: k, versions: list.map((e) => e.version) });
}

// 2-5. The editors.
const totals = { sent: 0, acked: 0, rejected: 0, rejectReasons: {}, lost: 0, lostThenInJournal: 0, unansweredToldByNotice: 0,
  unansweredInJournal: 0, unansweredNeverTold: 0, dupAnswers: 0, notices: 0, sessions: 0 };
const sent = new Map(); // "session/seq" -> {editor, outcome}
for (const name of editorNames) {
  const noticed = new Set(); // "session/seq" named pending in a notice
  for (const r of lines(`${name}.jsonl`)) {
    const k = `${r.session}/${r.seq}`;
    if (r.kind === 'session') ++totals.sessions;
    else if (r.kind === 'send') { ++totals.sent; sent.set(k, { editor: name, outcomes: [], t: r.t }); }
    else if (r.kind === 'notice') { ++totals.notices; for (const s of r.pending ?? []) noticed.add(`${r.session}/${s}`); }
    else if (['ack', 'reject', 'dup-ack', 'dup-reject', 'lost', 'unanswered-at-end'].includes(r.kind)) {
      const c = sent.get(k);
      if (!c) { finding('an answer to a command that was never sent', { editor: name, command: k, kind: r.kind }); continue; }
      c.outcomes.push(r);
      if (r.kind === 'unanswered-at-end') c.noticed = noticed.has(k);
    }
  }
}
for (const [k, c] of sent) {
  const inJournal = byCommand.get(k) ?? [];
  const acks = c.outcomes.filter((o) => o.kind === 'ack' || o.kind === 'dup-ack');
  const rejects = c.outcomes.filter((o) => o.kind === 'reject' || o.kind === 'dup-reject');
  totals.dupAnswers += c.outcomes.filter((o) => o.kind.startsWith('dup-')).length;
  if (new Set(acks.map((a) => a.version)).size > 1) finding('a command acknowledged twice with different versions', { command: k, versions: acks.map((a) => a.version) });
  if (acks.length && rejects.length) finding('a command both acknowledged and refused', { command: k, ack: acks[0].version, reject: rejects[0].message });
  if (acks.length) {
    ++totals.acked;
    const v = Number(acks[0].version);
    if (inJournal.length === 0) finding('an acknowledged edit is not in the journal', { command: k, editor: c.editor, version: v });
    else {
      const e = inJournal[0];
      if (Number(e.version) + 1 !== v) finding('an acknowledged edit is in the journal at another version', { command: k, ackVersion: v, journalVersion: Number(e.version) + 1 });
      if (e.author !== c.editor) finding('an acknowledged edit is in the journal under another author', { command: k, author: e.author, editor: c.editor });
    }
  } else if (rejects.length) {
    ++totals.rejected;
    const reason = rejects[0].reason;
    totals.rejectReasons[reason] = (totals.rejectReasons[reason] ?? 0) + 1;
    if (inJournal.length) finding('a refused command is in the journal', { command: k, reason, message: rejects[0].message, version: Number(inJournal[0].version) + 1 });
  } else if (c.outcomes.some((o) => o.kind === 'lost')) {
    ++totals.lost;
    if (inJournal.length) ++totals.lostThenInJournal;
  } else {
    // Unanswered with the connection still open at the end.
    if (inJournal.length) ++totals.unansweredInJournal;
    if (c.noticed) ++totals.unansweredToldByNotice;
    else {
      ++totals.unansweredNeverTold;
      finding('a command got no answer and its author was not told it may be lost', { command: k, editor: c.editor, inJournal: inJournal.length > 0 });
    }
  }
}
// How long commands waited for their answer (or, lost, for their
// connection to close): an answer that comes only minutes later is no
// finding by the rules above, so it is measured.
const waits = { answered: [], lost: [] };
for (const c of sent.values()) {
  const first = c.outcomes[0];
  if (!first) continue;
  if (first.kind === 'ack' || first.kind === 'reject') waits.answered.push(first.t - c.t);
  else if (first.kind === 'lost') waits.lost.push(first.t - c.t);
}
const spread = (xs) => {
  xs.sort((a, b) => a - b);
  const q = (p) => Number(xs[Math.min(xs.length - 1, Math.floor(p * xs.length))].toFixed(3));
  return xs.length ? { n: xs.length, p50_s: q(0.5), p99_s: q(0.99), max_s: q(1), over10s: xs.filter((x) => x > 10).length } : { n: 0 };
};
for (const [k, list] of byCommand) {
  if (!sent.has(k)) finding('a journal entry no editor sent', { command: k, version: Number(list[0].version) + 1, author: list[0].author });
}

// 6. The viewers and the end.
const journalVersion = String(lastVersion + 1);
const fresh = final.fresh ?? [];
const ref = fresh.find((f) => f.version) ?? null;
if (!ref) finding('no fresh subscriber got the document at the end', { fresh });
for (const f of fresh) {
  if (!f.version) { finding('a fresh subscriber got nothing at the end', { node: f.node, errors: f.errors }); continue; }
  if (f.version !== journalVersion) finding('a fresh subscriber\'s version is not the journal\'s', { node: f.node, version: f.version, journal: journalVersion });
  if (ref && (f.version !== ref.version || f.hash !== ref.hash)) finding('fresh subscribers on two nodes disagree', { node: f.node, version: f.version, hash: f.hash, ref });
  if (f.hash !== f.announced) finding('a fresh subscriber\'s assembled hash differs from the server\'s', { node: f.node, hash: f.hash, announced: f.announced });
}
for (const r of final.replaySurface ?? []) {
  const version = /version (\d+)/.exec(r.out)?.[1], hash = /surface_hash ([0-9a-f]+)/.exec(r.out)?.[1];
  if (r.status !== 0 || !version) { finding('tessera-replay surface failed at the end', r); continue; }
  if (ref && (version !== ref.version || `0x${hash}` !== ref.hash)) finding('tessera-replay surface disagrees with the fresh subscribers', { node: r.node, version, hash, ref });
}
const viewerSummary = [];
for (const v of final.viewers ?? []) {
  viewerSummary.push({ name: v.name, version: v.version, reconnects: v.reconnects, hashChecks: v.hashChecks, hashMismatches: v.hashMismatches });
  if (!v.ready || !ref || v.version !== ref.version || v.hash !== ref.hash) finding('a viewer did not converge to what a fresh subscriber sees', { viewer: v.name, version: v.version, hash: v.hash, ref: ref && { version: ref.version, hash: ref.hash } });
  if (v.hashMismatches > 0) finding('a viewer assembled a surface whose hash differs from the server\'s', { viewer: v.name, mismatches: v.hashMismatches });
}
if (final.baseManifest?.missing) finding('the document\'s base is missing from TESSERA_BLOBS at the end', { error: final.baseManifest.missing });

// 7. The journal replayed offline.
let offline = null;
if (existsSync(join(dir, 'offline.json'))) {
  offline = JSON.parse(readFileSync(join(dir, 'offline.json'), 'utf8'));
  if (!offline.ok) finding('the offline replay of the journal failed', { error: offline.error, log: offline.log });
  else {
    if (ref && (offline.replayed.version !== ref.version || offline.replayed.hash !== ref.hash)) {
      finding('the journal replayed offline differs from what the cluster serves', { offline: offline.replayed, cluster: { version: ref.version, hash: ref.hash } });
    }
    const v1 = viewerNames.flatMap((n) => lines(`${n}.jsonl`)).find((r) => r.kind === 'snapshot' && r.version === '1');
    if (v1 && v1.hash !== offline.base.hash) finding('the offline base differs from the cluster\'s version 1', { offline: offline.base, cluster: v1.hash });
  }
}

// Time from each fault's heal (or, for a client's move, the fault itself)
// to the next acknowledgement of any editor.
const ackTimes = editorNames.flatMap((n) => lines(`${n}.jsonl`)).filter((r) => r.kind === 'ack').map((r) => r.t).sort((a, b) => a - b);
const nextAck = (t) => { let lo = 0, hi = ackTimes.length; while (lo < hi) { const m = (lo + hi) >> 1; if (ackTimes[m] < t) lo = m + 1; else hi = m; } return lo < ackTimes.length ? ackTimes[lo] - t : null; };
const recovery = {};
for (const e of events) {
  const instant = e.what === 'fault' && e.kind === 'client-moves';
  if (!(e.what === 'heal' || instant)) continue;
  const d = nextAck(e.t);
  (recovery[e.kind] ??= []).push(d === null ? Infinity : d);
}
const quantile = (xs, q) => xs[Math.min(xs.length - 1, Math.floor(q * xs.length))];
// Infinity: no acknowledgement came after it (the last fault before the
// editors stopped), counted apart.
const recoverySummary = Object.fromEntries(Object.entries(recovery).map(([k, all]) => {
  const xs = all.filter(Number.isFinite).sort((a, b) => a - b);
  const r = { n: xs.length, noAckAfter: all.length - xs.length };
  if (xs.length) Object.assign(r, { p50_s: Number(quantile(xs, 0.5).toFixed(2)), p90_s: Number(quantile(xs, 0.9).toFixed(2)), max_s: Number(xs[xs.length - 1].toFixed(2)) });
  return [k, r];
}));

const viewerEvents = {};
for (const name of viewerNames) {
  for (const r of lines(`${name}.jsonl`)) viewerEvents[r.kind] = (viewerEvents[r.kind] ?? 0) + 1;
}

const faults = {};
for (const e of events) if (e.what === 'fault') faults[e.kind] = (faults[e.kind] ?? 0) + 1;
const findingKinds = {};
for (const f of findings) findingKinds[f.what] = (findingKinds[f.what] ?? 0) + 1;
const summary = {
  seed: final.seed, elapsed_s: Math.round(final.elapsed_s), faults, faultsTotal: Object.values(faults).reduce((a, b) => a + b, 0),
  commands: totals, secondsToAnswer: spread(waits.answered), secondsPendingBeforeLost: spread(waits.lost), journal: { messages: journal.length, entries: entries.length, fences, lastDocumentVersion: Number(journalVersion) },
  end: { fresh: fresh.map((f) => `node${f.node} v${f.version} ${f.hash}`), replaySurface: (final.replaySurface ?? []).map((r) => r.out.replace(/\n/g, ' ')) },
  offlineReplay: offline ? (offline.ok ? { ...offline.replayed, entries: offline.entries, base: offline.base } : { error: offline.error }) : 'not run',
  secondsFromHealToNextAck: recoverySummary,
  viewers: viewerSummary, viewerEvents, findingKinds, findings: findings.slice(0, 200),
};
writeFileSync(join(dir, 'summary.json'), JSON.stringify(summary, null, 2));
console.log(JSON.stringify({ ...summary, findings: findings.slice(0, 20) }, null, 2));
console.log(findings.length ? `FAIL: ${findings.length} finding(s); see ${join(dir, 'summary.json')}` : 'PASS: no finding');
process.exit(findings.length ? 1 : 0);
