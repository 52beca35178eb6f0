// One document over one connection: what client/view/connection.cc does
// for tessera-view, without the transport. On every (re)connection it opens
// the document and subscribes with the chosen LOD profile; it feeds
// snapshots and deltas into a DocumentView, subscribes again after a gap,
// checks the surface hash against the server's, keeps the collaborators
// from Presence, sends this viewer's edits (paced, each in an undo step)
// and measures edit-to-delta latency.
import { DocumentView, regionPayloads } from './document_view.js';
import { OrderedUpdates } from './ordered_updates.js';
import { UndoHistory } from './undo_history.js';
import { LatencyTracker } from './latency.js';
import { Collaborators } from './presence.js';
import { Pacer } from './pacer.js';
import { toBig, toLong, hex64 } from '../codec/uint64.js';
import { shallower } from './lod_profiles.js';
import { RejectError } from './connection.js';

// SetEdgeSharpness.edge_id when end_vertex_ids name the edge (7.2).
const EDGE_NAMED_BY_ENDS = (1n << 64n) - 1n;

export class DocumentSession {
  // options: {connection, decode (bytes -> a decoded region, or a Promise
  // of one: the page's Web Worker), documentId, profile, codec ('draco',
  // the default, or 'meshopt': profiles only), view (a View's
  // fields: a view-dependent subscription, PROTOCOL.md section 16; null for
  // a profile), onView(change), onPresence(), onStatus(text),
  // onError(text), onHash(result), onProfileOnly() (a view was asked for
  // but the document takes none -- a morph, or a Catmull-Clark document,
  // docs/LIMITS.md -- so it is subscribed with the profile)}.
  constructor(options) {
    this.o = options;
    this.connection = options.connection;
    this.documentId = BigInt(options.documentId);
    this.profile = options.profile;
    // 'draco' or 'meshopt': the page's choice, read at every subscription.
    this.codec = options.codec ?? 'draco';
    this.camera = options.view ?? null; // the latest view sent, for (re)subscribing
    this.cameraSeq = 0n; // the client_seq of the latest SetView sent
    this.view = new DocumentView(this.documentId);
    // Snapshots and deltas in arrival order, whenever their regions decode
    // (docs/WEB_VIEWER.md "Decoding in a worker").
    this.updates = new OrderedUpdates({
      decode: options.decode,
      payloads: regionPayloads,
      needsRegions: (body, message) => this.view.needsRegions(body, message),
      apply: (body, message, decoded) => this.update(body, message, decoded),
    });
    this.history = new UndoHistory();
    this.latency = new LatencyTracker();
    this.collaborators = new Collaborators();
    this.pacer = new Pacer();
    this.role = 0; // the role on this document, from our own Presence entry
    this.sessionId = 0n;
    this.opened = false;
    this.editsSent = 0;
    this.editsRejected = 0;
    this.hashChecks = 0;
    this.hashMismatches = 0;
    this.lastHash = null; // {ours, server, matches}
  }

  // Called by the page once the connection has its HelloAck.
  async connected(helloAck) {
    this.sessionId = toBig(helloAck.session_id);
    this.role = helloAck.role;
    this.pacer.clear(); // commands for the lost connection's session
    this.updates.reset(); // the lost connection's messages: not for the new view
    this.view = new DocumentView(this.documentId);
    this.latency.reset();
    this.collaborators.clear();
    this.opened = false;
    try {
      await this.connection.call({ open_document: { document_id: toLong(this.documentId) } });
      this.opened = true;
      // A morph document is shown with the profile: its time, morph_t, is a
      // profile field (PROTOCOL.md section 14; docs/WEB_VIEWER.md "Views").
      if (this.camera && await this.isMorph()) {
        this.camera = null;
        this.o.onProfileOnly?.();
      }
      this.o.onStatus?.('subscribing');
      await this.subscribeOrShallower(this.profile);
    } catch (error) {
      this.o.onError?.(`document ${this.documentId}: ${error.message}`);
    }
  }

  // Only a morph document answers GetMorphControl with its control points;
  // one with a single key is refused (PROTOCOL.md section 14). Without
  // with_topology the answer is the base points at t = 0.
  async isMorph() {
    try {
      const reply = await this.connection.call({ get_morph_control: { document_id: toLong(this.documentId) } });
      return Boolean(reply.message.morph_control);
    } catch (error) {
      if (!(error instanceof RejectError)) throw error; // the connection was lost
      return false;
    }
  }

  // A document's max_level is not known over the wire (12 of PROTOCOL.md),
  // so a profile it refuses as invalid or too large is tried again one
  // level shallower until one is accepted.
  async subscribeOrShallower(profile) {
    for (let p = profile; ;) {
      try {
        const version = await this.subscribe(p);
        this.o.onProfile?.(p);
        return version;
      } catch (error) {
        if (this.camera && error instanceof RejectError) {
          // A view refused (a document that takes none): the profile.
          this.camera = null;
          this.o.onError?.(`view refused (${error.message}); showing the LOD profile`);
          this.o.onProfileOnly?.();
          continue;
        }
        const next = error.reason === 1 || error.reason === 7 ? shallower(p) : null; // INVALID_ARGUMENT, LIMIT_EXCEEDED
        if (!next) throw error;
        this.o.onError?.(`LOD ${p.name ?? ''} refused (${error.message}); trying max level ${next.maxLevel}`);
        p = next;
      }
    }
  }

  // Subscribing again with another profile replaces the old one (6.1).
  async subscribe(profile) {
    this.profile = profile;
    const subscribe = { document_id: toLong(this.documentId), profile: profileFields(profile) };
    if (this.camera) subscribe.view = this.camera;
    // tessera.proto RegionCodec: REGION_CODEC_MESHOPT = 2, for profiles only
    // (a view's tiles are Draco); the decode worker reads either.
    else if (this.codec === 'meshopt') subscribe.codec = 2;
    this.cameraSeq = 0n; // the subscription carries the latest camera
    const reply = await this.connection.call({ subscribe });
    return toBig(reply.message.ack.version);
  }

  // A view-dependent subscription: the camera moved. No reply unless refused.
  // False when it could not go now (not subscribed yet): offer it again.
  setView(view) {
    if (!this.opened || !this.view.ready) return false;
    try {
      this.cameraSeq = BigInt(this.connection.send({ set_view: { document_id: toLong(this.documentId), view } }));
      this.camera = view;
      return true;
    } catch (error) {
      this.o.onError?.(`set view: ${error.message}`);
      return false;
    }
  }

  // The tiles of the latest camera sent are all here.
  viewComplete() {
    return this.camera !== null && this.view.ready && this.view.viewComplete && this.view.viewSeq === this.cameraSeq;
  }

  resubscribe(reason) {
    this.o.onError?.(`${reason}; subscribing again`);
    this.subscribe(this.profile).catch((error) => this.o.onError?.(`subscribe: ${error.message}`));
  }

  // Server messages that are not replies.
  message(body, message) {
    if (body === 'snapshot' || body === 'delta') return this.updates.push(body, message);
    if (body === 'presence' && toBig(message.presence.document_id) === this.documentId) {
      this.collaborators.apply(message.presence);
      const self = this.collaborators.bySession.get(this.sessionId);
      if (self) this.role = self.role;
      this.o.onPresence?.();
    }
  }

  // One message, its turn come; decoded: its regions' results (one {region}
  // or {error} each), or null when the view does not read them.
  update(body, message, decoded) {
    let change;
    try {
      change = this.view.apply(body, message, decoded);
    } catch (error) {
      // A region that does not decode: the view cannot be trusted.
      this.view.gap(error.message);
      change = { kind: 'gap', reason: error.message };
    }
    if (change.kind === 'gap') return this.resubscribe(change.reason);
    if (change.kind === 'delta') {
      const d = change.delta;
      this.latency.delta(toBig(d.from_version), toBig(d.to_version), toBig(d.author_session_id) === this.sessionId);
    }
    if (change.kind === 'snapshot' || change.kind === 'delta') {
      this.checkHash();
      this.o.onView?.(change);
    }
  }

  checkHash() {
    const ours = this.view.surfaceHash();
    const server = this.view.announcedHash;
    const matches = server === 0n || server === ours;
    ++this.hashChecks;
    if (!matches) {
      ++this.hashMismatches;
      this.o.onError?.(`version ${this.view.version}: surface hash ${hex64(ours)}, the server's ${hex64(server)}: ` +
        'the assembled regions differ from the server\'s');
    }
    this.lastHash = { ours, server, matches };
    this.o.onHash?.(this.lastHash);
  }

  canEdit() {
    return this.opened && this.role >= 2; // ROLE_EDITOR or ROLE_ADMIN
  }

  // Sends an edit (paced), counting it in `step` (a new step of its own
  // when none is given).
  edit(command, step = null) {
    const own = step === null;
    if (own) step = this.history.open();
    this.history.sent(step);
    if (own) this.history.close(step);
    const job = () => {
      ++this.editsSent;
      this.connection.call(command).then(
        (reply) => {
          const ack = reply.message.ack;
          if (ack && toBig(ack.edit_id) !== 0n) this.history.acked(step, toBig(ack.edit_id));
          else this.history.dropped(step);
          if (ack) this.latency.acked(toBig(ack.version), reply.sentAt, this.view.version);
        },
        (error) => {
          ++this.editsRejected;
          this.history.dropped(step);
          this.o.onError?.(error.message);
        });
    };
    job.drop = () => this.history.dropped(step);
    this.pacer.run(job);
  }

  moveVertex(vertexId, target, step) {
    this.edit({
      move_vertex: {
        document_id: toLong(this.documentId),
        vertex_ids: [toLong(vertexId)],
        target: { x: target[0], y: target[1], z: target[2] },
        mode: 1, // MOVE_MODE_DIRECT_MANIPULATION
      },
    }, step);
  }

  setEdgeSharpness(endA, endB, sharpness) {
    this.edit({
      set_edge_sharpness: {
        document_id: toLong(this.documentId),
        edge_id: toLong(EDGE_NAMED_BY_ENDS),
        end_vertex_ids: [toLong(endA), toLong(endB)],
        sharpness,
      },
    });
  }

  // type: 1 smooth, 3 corner (VertexType).
  setVertexType(vertexId, type) {
    this.edit({ set_vertex_type: { document_id: toLong(this.documentId), vertex_id: toLong(vertexId), type } });
  }

  // Others see it in Presence; a valid Select has no reply (7.2).
  select(vertexIds) {
    if (!this.opened) return;
    try {
      this.connection.send({
        select: { document_id: toLong(this.documentId), selection: { vertex_ids: vertexIds.map((id) => toLong(id)) } },
      });
    } catch (error) {
      this.o.onError?.(`select: ${error.message}`);
    }
  }

  // The polygons of `level`'s control mesh (GetCage; docs/WEB_VIEWER.md
  // "The control cage"): resolves with the Cage message, or rejects with a
  // RejectError (a level beyond the document's max, too many faces) or a
  // lost connection.
  async cage(level) {
    const reply = await this.connection.call({ get_cage: { document_id: toLong(this.documentId), level } });
    return reply.message.cage;
  }

  // Undo (or redo) this viewer's newest step: one Undo per edit, newest
  // first (redo: oldest first). False with the reason shown when nothing can.
  step(undo) {
    let ids;
    try {
      ids = undo ? this.history.undo() : this.history.redo();
    } catch (error) {
      this.o.onError?.(error.message);
      return false;
    }
    for (const id of ids) {
      const command = undo
        ? { undo: { document_id: toLong(this.documentId), edit_id: toLong(id) } }
        : { redo: { document_id: toLong(this.documentId), edit_id: toLong(id) } };
      this.pacer.run(() => {
        const sentAt = performance.now();
        this.connection.call(command).then(
          (reply) => this.latency.acked(toBig(reply.message.ack.version), sentAt, this.view.version),
          (error) => this.o.onError?.(error.message));
      });
    }
    return true;
  }
}

// A profile of lod_profiles.js as LodProfile fields.
export function profileFields(p) {
  return {
    base_level: p.baseLevel,
    max_level: p.maxLevel,
    angle_threshold_degrees: p.angle,
    triangle_budget: toLong(p.budget ?? 0),
    omit_vertex_ids: Boolean(p.omitVertexIds),
  };
}
