// The control-cage toggle (docs/WEB_VIEWER.md "The control cage"): while on,
// the cage of the control level the dots show is asked for with GetCage once
// the document is open, and handed to the layer. A cage is topology only and
// no edit changes a level's faces, so each level's answer is kept for the
// document and asked for once; a refused level (the server's Reject: above
// the document's max level, too many faces) is shown and not asked again; a
// request lost with the connection is asked again after reconnecting.
import { RejectError } from '../session/connection.js';
import { cageEdges } from '../scene/control_cage.js';

export class CageControl {
  // options: {layer (CageLayer), session(): DocumentSession or null,
  // level(): the control level shown, onError(text)}
  constructor(options) {
    this.o = options;
    this.on = false;
    this.session = null; // the session the kept answers belong to
    this.cages = new Map(); // level -> cageEdges' result
    this.refused = new Map(); // level -> the server's message
    this.asking = new Set(); // levels asked for, not answered yet
    this.requests = 0; // GetCage requests sent
  }

  setOn(on) {
    this.on = on;
    this.sync();
  }

  toggle() {
    this.setOn(!this.on);
  }

  // After anything that may change what is drawn: the toggle, the level,
  // the session opening.
  sync() {
    const session = this.o.session();
    if (session !== this.session) {
      this.session = session;
      this.cages.clear();
      this.refused.clear();
      this.asking.clear();
    }
    const level = this.o.level();
    this.show();
    if (!this.on || !session?.opened || this.cages.has(level) || this.refused.has(level) || this.asking.has(level)) return;
    this.ask(session, level);
  }

  // The layer draws the kept cage of the level shown, if on.
  show() {
    this.o.layer.setCage(this.on ? this.cages.get(this.o.level()) ?? null : null);
  }

  async ask(session, level) {
    this.asking.add(level);
    ++this.requests;
    try {
      const cage = cageEdges(await session.cage(level));
      if (session !== this.session) return;
      this.cages.set(level, cage);
    } catch (error) {
      if (session !== this.session) return;
      // A lost connection is asked again at the next sync (not at once: a
      // connection that is down fails at once, again and again); a refusal
      // or a reply that does not describe polygons is not asked again.
      if (error instanceof RejectError || error instanceof RangeError) {
        this.refused.set(level, error.message);
        this.o.onError(`control cage of level ${level}: ${error.message}`);
      }
    } finally {
      if (session === this.session) this.asking.delete(level);
    }
    this.show();
  }

  // For the panel and the test hook: {on, level, status ('off', 'asking',
  // 'shown', 'too large', 'refused', 'waiting'), faces, edges, faceSizes,
  // segments (drawn in the last frame), requests}.
  facts() {
    const level = this.o.level();
    const cage = this.on ? this.cages.get(level) : undefined;
    const status = !this.on ? 'off'
      : cage ? (this.o.layer.tooLarge ? 'too large' : 'shown')
        : this.refused.has(level) ? 'refused'
          : this.asking.has(level) ? 'asking' : 'waiting';
    return {
      on: this.on, level, status,
      faces: cage?.faces ?? 0, edges: cage?.edges.length ?? 0, faceSizes: cage ? { ...cage.faceSizes } : {},
      segments: cage ? this.o.layer.segments : 0,
      requests: this.requests,
    };
  }
}
