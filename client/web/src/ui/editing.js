// Picking and editing with the mouse and keyboard (docs/VIEWER.md
// "Controls", adapted to the browser):
//   - a press near a control vertex of the edit level picks it (Select, so
//     collaborators see it) and, with the editor role, drags it: MoveVertex
//     in DIRECT_MANIPULATION mode with the target limit position in the
//     plane facing the camera, at most 30 a second and once more on
//     release; the whole drag is one undo step. A press elsewhere orbits.
//   - Ctrl+Z undo, Ctrl+Y or Ctrl+Shift+Z redo (one step each);
//   - C crease toggle on the edge between the last two picked vertices
//     (SetEdgeSharpness by its end vertices, +inf or 0);
//   - V the last picked vertex: corner, or smooth again (SetVertexType);
//   - W wireframe, R region colours, F fit, [ ] edit level, P control
//     points, O the control cage, H fold the HUD, Esc drop the picks.
import { packId, idName } from '../codec/ids.js';

const SEND_INTERVAL_MS = 33; // ~30 edits a second while dragging
const CORNER = 3, SMOOTH = 1; // VertexType

export class Editor {
  // options: {element, view (SceneView), picker, vertices, controlPoints,
  // session(): DocumentSession or null, maxLevel(): profile max level,
  // level: the first edit level (default 1), onChange(), onError(text),
  // toggleHud(), toggleCage()}
  constructor(options) {
    this.o = options;
    this.level = options.level ?? 1; // the control level edited
    this.picks = []; // the last two picked vertex ids (BigInt, at this.level)
    this.hover = null;
    this.drag = null;
    this.corners = new Set(); // vertex ids this viewer made corners
    this.creased = new Set(); // "a-b" edges this viewer made sharp
    const el = options.element;
    // Capture: before OrbitControls sees the press, so a drag does not orbit.
    el.addEventListener('pointerdown', (e) => this.down(e), { capture: true });
    el.addEventListener('pointermove', (e) => this.move(e));
    el.addEventListener('pointerup', (e) => this.up(e));
    el.addEventListener('pointercancel', (e) => this.up(e));
    window.addEventListener('keydown', (e) => this.key(e));
  }

  session() {
    const s = this.o.session();
    return s && s.opened && s.view.ready ? s : null;
  }

  // The level edited stays within the profile's levels.
  clampLevel() {
    this.level = Math.max(0, Math.min(this.level, this.o.maxLevel()));
  }

  idOf(vertex) {
    return packId(this.level, vertex.index);
  }

  down(event) {
    if (event.button !== 0 || event.shiftKey || event.ctrlKey || event.metaKey) return;
    const session = this.session();
    if (!session) return;
    const vertex = this.o.picker.pick(event.clientX, event.clientY, this.level);
    if (!vertex) return;
    event.stopImmediatePropagation();
    this.o.view.controls.enabled = false;
    this.o.element.setPointerCapture?.(event.pointerId);
    const id = this.idOf(vertex);
    this.picks = [...this.picks.filter((p) => p !== id).slice(-1), id];
    session.select([id]);
    this.drag = { id, anchor: vertex.position, step: null, lastSent: 0, pending: null, timer: null, session };
    if (session.canEdit()) this.drag.step = session.history.open();
    this.o.onChange();
  }

  move(event) {
    if (!this.drag) {
      if (event.buttons !== 0) return; // orbiting or panning
      const vertex = this.session() ? this.o.picker.pick(event.clientX, event.clientY, this.level) : null;
      if (vertex !== this.hover) {
        this.hover = vertex;
        this.o.controlPoints.setHover(vertex);
      }
      return;
    }
    if (this.drag.step === null) return; // a viewer picks but does not drag
    this.drag.pending = this.o.picker.dragTarget(event.clientX, event.clientY, this.drag.anchor);
    this.flush(false);
  }

  // Sends the pending target if the interval has passed (or `now`), else
  // once it has.
  flush(now) {
    const d = this.drag;
    if (!d || !d.pending) return;
    const wait = d.lastSent + SEND_INTERVAL_MS - performance.now();
    if (!now && wait > 0) {
      if (!d.timer) d.timer = setTimeout(() => { d.timer = null; this.flush(false); }, wait);
      return;
    }
    clearTimeout(d.timer);
    d.timer = null;
    d.session.moveVertex(d.id, d.pending, d.step);
    d.pending = null;
    d.lastSent = performance.now();
  }

  // After the surface changed: the ring follows the vertex it marks.
  refreshHover() {
    if (!this.hover) return;
    this.hover = this.o.vertices.lookup(packId(this.level, this.hover.index));
    this.o.controlPoints.setHover(this.hover);
  }

  up(event) {
    const d = this.drag;
    if (!d) return;
    this.flush(true);
    if (d.step !== null) d.session.history.close(d.step);
    this.drag = null;
    this.o.view.controls.enabled = true;
    this.o.element.releasePointerCapture?.(event.pointerId);
    this.o.onChange();
  }

  key(event) {
    if (event.target instanceof HTMLElement && event.target.closest('input, select, textarea, button')) return;
    const k = event.key.toLowerCase();
    const ctrl = event.ctrlKey || event.metaKey;
    const session = this.session();
    if (ctrl && (k === 'z' || k === 'y')) {
      event.preventDefault();
      if (session) session.step(k === 'z' && !event.shiftKey);
    } else if (ctrl || event.altKey) {
      return;
    } else if (k === 'w') {
      this.o.view.setWireframe(!this.o.view.wireframe);
    } else if (k === 'r') {
      this.o.view.setRegionColours(!this.o.view.regionColours);
    } else if (k === 'f') {
      this.o.view.fit();
    } else if (k === 'h') {
      this.o.toggleHud();
    } else if (k === 'p') {
      this.o.controlPoints.visible = !this.o.controlPoints.visible;
    } else if (k === 'o') {
      this.o.toggleCage();
    } else if (k === '[' || k === ']') {
      this.setLevel(this.level + (k === ']' ? 1 : -1));
    } else if (k === 'escape') {
      this.picks = [];
      session?.select([]);
    } else if (k === 'c' && session) {
      this.toggleCrease(session);
    } else if (k === 'v' && session) {
      this.cycleVertexType(session);
    } else {
      return;
    }
    this.o.onChange();
  }

  setLevel(level) {
    this.level = level;
    this.clampLevel();
    this.picks = [];
    this.hover = null;
    this.o.controlPoints.setHover(null);
  }

  toggleCrease(session) {
    if (this.picks.length < 2) {
      this.o.onError('C needs an edge: pick its two end vertices first');
      return;
    }
    const [a, b] = this.picks;
    const key = a < b ? `${a}-${b}` : `${b}-${a}`;
    const sharp = !this.creased.has(key);
    session.setEdgeSharpness(a, b, sharp ? Infinity : 0);
    if (sharp) this.creased.add(key); else this.creased.delete(key);
  }

  cycleVertexType(session) {
    if (this.picks.length === 0) {
      this.o.onError('V needs a picked vertex');
      return;
    }
    const id = this.picks[this.picks.length - 1];
    const corner = !this.corners.has(id);
    session.setVertexType(id, corner ? CORNER : SMOOTH);
    if (corner) this.corners.add(id); else this.corners.delete(id);
  }

  // For the HUD: what is picked, in people's terms.
  describe() {
    if (this.picks.length === 0) return 'nothing picked';
    if (this.picks.length === 1) return `picked ${idName(this.picks[0])}`;
    return `edge ${idName(this.picks[0])} – ${idName(this.picks[1])}`;
  }
}
