// One document as this subscriber sees it (client/lib/document_view.cc):
// the decoded regions of its LOD profile, kept current by snapshots and
// deltas with version continuity checked (docs/PROTOCOL.md 6.1).
//
//   - Snapshot parts go to a staging set; the last part (remaining_parts 0)
//     replaces every region and sets the version. The view is then ready.
//   - A delta before the first snapshot, or after a gap, is ignored.
//   - A delta with from_version == version replaces or adds its regions in
//     order (a merged delta may list a region twice), drops the removed ids
//     and moves to to_version.
//   - Any other delta, or a flag-2 region whose layout the view does not
//     hold, is a gap: the view stops until the next snapshot, and apply()
//     says so, so that the caller subscribes again.
//
// The regions may come decoded already (the page decodes them in a Web
// Worker, session/ordered_updates.js): apply() then takes one settled result
// per payload and meets a decoding error at the same point, with the same
// message, as it would decoding here (docs/WEB_VIEWER.md "Decoding in a
// worker").
import { adoptLayoutIds } from '../codec/region_decoder.js';
import { regionHash, sumHashes } from '../codec/surface_hash.js';
import { toBig } from '../codec/uint64.js';

const IGNORED = Object.freeze({ kind: 'ignored' });

// The region payloads (Uint8Arrays) of a Snapshot or Delta message, in order.
export function regionPayloads(body, message) {
  if (body === 'snapshot') return message.snapshot.regions.map((r) => r.draco);
  if (body === 'delta') return message.delta.regions.map((r) => r.draco);
  return [];
}

export class DocumentView {
  // decode(bytes) -> decoded region (codec/region_decoder.js, bound to
  // Draco); used only when apply() is not given the regions decoded.
  constructor(documentId, decode = null) {
    this.documentId = BigInt(documentId);
    this.decode = decode;
    this.regions = new Map(); // region id (BigInt) -> decoded region
    this.staging = new Map();
    this.stagingVersion = null;
    this.version = 0n;
    this.ready = false;
    this.gaps = 0;
    this.announcedHash = 0n; // the server's surface hash for `version`
    this.regionBytes = 0;
    // A view-dependent subscription: the last delta said the tiles of the
    // view it names (Delta.view_seq, the SetView's client_seq) are all here.
    this.viewComplete = false;
    this.viewSeq = 0n;
    // The first whole snapshot, as it came (the test hook's): its region ids
    // (decimal strings, sorted), their payloads' bytes and triangles.
    this.firstSnapshot = null;
  }

  // Applies a Snapshot or Delta message body ({snapshot} or {delta} of the
  // ServerMessage). Returns what changed: {kind: 'part'} for a snapshot part
  // still waiting for the rest, {kind: 'snapshot', regions} when the whole
  // set was replaced, {kind: 'delta', changed, removed, delta}, {kind:
  // 'ignored'}, or {kind: 'gap', reason}.
  //
  // decoded: null to decode here, or one settled result per payload of
  // regionPayloads(), {region} or {error}; an error is thrown where the
  // decoder would have thrown it.
  apply(body, message, decoded = null) {
    const take = (r, index) => {
      if (!decoded) return this.decode(r.draco);
      const result = decoded[index];
      if (result.error) throw result.error;
      return result.region;
    };
    if (body === 'snapshot') return this.applySnapshot(message.snapshot, take);
    if (body === 'delta') return this.applyDelta(message.delta, take);
    return IGNORED;
  }

  // What apply() decides before it looks at any region: IGNORED, a gap
  // ({kind: 'gap', reason}, not yet counted), or null when it needs the
  // regions. Against the view as it is now: a message queued behind others
  // is asked when its turn comes.
  verdictBeforeRegions(body, message) {
    if (body === 'snapshot') return toBig(message.snapshot.document_id) === this.documentId ? null : IGNORED;
    if (body !== 'delta') return IGNORED;
    const d = message.delta;
    if (toBig(d.document_id) !== this.documentId || !this.ready) return IGNORED;
    const from = toBig(d.from_version), to = toBig(d.to_version);
    if (from !== this.version) {
      return { kind: 'gap', reason: `document ${this.documentId}: delta ${from}->${to} does not follow version ${this.version}` };
    }
    return null;
  }

  // Whether apply() will read this message's regions, now.
  needsRegions(body, message) {
    return this.verdictBeforeRegions(body, message) === null;
  }

  applySnapshot(s, take) {
    if (toBig(s.document_id) !== this.documentId) return IGNORED;
    const version = toBig(s.version);
    // Parts of one snapshot share its version; a part of another starts over.
    if (this.stagingVersion !== version) {
      this.staging = new Map();
      this.stagingVersion = version;
    }
    for (const [index, r] of s.regions.entries()) {
      const decoded = this.decodePayload(r, index, take);
      if (!decoded.header.idsInline && decoded.header.hasIds) {
        // Snapshots always carry ids (6.2): one without them cannot be
        // assembled, so ask for another.
        this.staging = new Map();
        this.stagingVersion = null;
        return this.gap(`document ${this.documentId}: snapshot region ${toBig(r.region_id)} comes without its ids`);
      }
      this.staging.set(toBig(r.region_id), decoded);
    }
    if (s.remaining_parts !== 0) return { kind: 'part' };
    this.firstSnapshot ??= {
      ids: [...this.staging.keys()].map(String).sort(),
      bytes: [...this.staging.values()].reduce((n, r) => n + r.bytes, 0),
      triangles: [...this.staging.values()].reduce((n, r) => n + r.indices.length / 3, 0),
    };
    this.regions = this.staging;
    this.staging = new Map();
    this.stagingVersion = null;
    this.version = version;
    this.announcedHash = toBig(s.surface_hash);
    this.ready = true;
    this.viewComplete = false;
    this.viewSeq = 0n;
    return { kind: 'snapshot', regions: this.regions, resync: s.resync };
  }

  applyDelta(d, take) {
    const verdict = this.verdictBeforeRegions('delta', { delta: d });
    if (verdict) return verdict.kind === 'gap' ? this.gap(verdict.reason) : verdict;
    const to = toBig(d.to_version);
    const changed = [];
    const updates = new Map();
    for (const [index, r] of d.regions.entries()) {
      const id = toBig(r.region_id);
      const decoded = this.decodePayload(r, index, take);
      if (!decoded.header.idsInline && decoded.header.hasIds) {
        const held = updates.get(id) ?? this.regions.get(id);
        try {
          adoptLayoutIds(decoded, held, held?.header.layoutVersion);
        } catch (error) {
          return this.gap(error.message); // ids this view does not hold: as good as a gap
        }
      }
      updates.set(id, decoded);
      changed.push(id);
    }
    for (const [id, region] of updates) this.regions.set(id, region);
    const removed = d.removed_region_ids.map(toBig);
    for (const id of removed) this.regions.delete(id);
    this.version = to;
    this.announcedHash = toBig(d.surface_hash);
    this.viewComplete = Boolean(d.view_complete);
    this.viewSeq = toBig(d.view_seq ?? 0);
    return { kind: 'delta', changed: [...new Set(changed)], removed, delta: d };
  }

  // A region of a Snapshot or Delta, decoded; it keeps its payload's size
  // (`bytes`: what the page's first picture cost, for the test hook).
  decodePayload(r, index, take) {
    this.regionBytes += r.draco.length;
    const decoded = take(r, index);
    decoded.bytes = r.draco.length;
    return decoded;
  }

  gap(reason) {
    ++this.gaps;
    this.ready = false;
    return { kind: 'gap', reason };
  }

  triangles() {
    let n = 0;
    for (const r of this.regions.values()) n += r.indices.length / 3;
    return n;
  }

  // The surface hash of 6.5 over the regions held; each region is hashed
  // once, the first time it is asked for after it arrived.
  surfaceHash() {
    const hashes = [];
    for (const r of this.regions.values()) {
      if (r.hash === undefined) r.hash = regionHash(r);
      hashes.push(r.hash);
    }
    return sumHashes(hashes);
  }

  // True when the server sent no hash (0) or it equals ours.
  hashMatches() {
    return this.announcedHash === 0n || this.announcedHash === this.surfaceHash();
  }
}
