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
import { adoptLayoutIds } from '../codec/region_decoder.js';
import { regionHash, sumHashes } from '../codec/surface_hash.js';
import { toBig } from '../codec/uint64.js';

export class DocumentView {
  // decode(bytes) -> decoded region (codec/region_decoder.js, bound to Draco).
  constructor(documentId, decode) {
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
  apply(body, message) {
    if (body === 'snapshot') return this.applySnapshot(message.snapshot);
    if (body === 'delta') return this.applyDelta(message.delta);
    return { kind: 'ignored' };
  }

  applySnapshot(s) {
    if (toBig(s.document_id) !== this.documentId) return { kind: 'ignored' };
    const version = toBig(s.version);
    // Parts of one snapshot share its version; a part of another starts over.
    if (this.stagingVersion !== version) {
      this.staging = new Map();
      this.stagingVersion = version;
    }
    for (const r of s.regions) {
      const decoded = this.decodePayload(r);
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

  applyDelta(d) {
    if (toBig(d.document_id) !== this.documentId || !this.ready) return { kind: 'ignored' };
    const from = toBig(d.from_version), to = toBig(d.to_version);
    if (from !== this.version) {
      return this.gap(`document ${this.documentId}: delta ${from}->${to} does not follow version ${this.version}`);
    }
    const changed = [];
    const updates = new Map();
    for (const r of d.regions) {
      const id = toBig(r.region_id);
      const decoded = this.decodePayload(r);
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
  decodePayload(r) {
    this.regionBytes += r.draco.length;
    const decoded = this.decode(r.draco);
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
