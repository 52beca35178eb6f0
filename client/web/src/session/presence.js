// Who else has the document open, and what they selected (docs/PROTOCOL.md
// 6.3). A full Presence replaces the list; a change-form one replaces the
// entries it names and removes those in left_session_ids. The marks that
// show the selections are scene/presence_layer.js.
import { toBig } from '../codec/uint64.js';

export class Collaborators {
  constructor() {
    this.bySession = new Map(); // session id (BigInt) -> {sessionId, name, role, selection: BigInt[]}
  }

  apply(presence) {
    if (presence.full) this.bySession.clear();
    for (const left of presence.left_session_ids) this.bySession.delete(toBig(left));
    for (const p of presence.participants) {
      const sessionId = toBig(p.session_id);
      this.bySession.set(sessionId, {
        sessionId,
        name: p.name,
        role: p.role,
        selection: (p.selection?.vertex_ids ?? []).map(toBig),
      });
    }
  }

  clear() {
    this.bySession.clear();
  }

  // In session order, as the server orders them.
  list() {
    return [...this.bySession.values()].sort((a, b) => (a.sessionId < b.sessionId ? -1 : a.sessionId > b.sessionId ? 1 : 0));
  }
}
