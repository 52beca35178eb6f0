// The heads-up display: a compact panel in the top-left corner, at most a
// third of the page wide and under half its height (it scrolls beyond), so
// that it never covers the middle of the frame where fit-to-view puts the
// model. Its first line carries what one wants at a glance (version,
// triangles, frame rate); then latency, bytes per second, the surface hash
// check, the LOD profile and the display toggles, the control cage's
// counts, the pick, the collaborators, and a status and an error line. H
// folds it to its first line, and on a phone-sized page it starts so. It
// only reads facts handed to it; it owns no state of the document.
import { LOD_PRESETS } from '../session/lod_profiles.js';
import { idName } from '../codec/ids.js';
import { hex64 } from '../codec/uint64.js';
import { sessionColour } from '../scene/presence_layer.js';

const ROLE_NAMES = ['no role', 'viewer', 'editor', 'admin'];
const SMALL_PAGE = '(max-width: 600px), (max-height: 500px)';

function shortCount(n) {
  if (n < 1e4) return String(Math.round(n));
  if (n < 1e6) return `${(n / 1e3).toFixed(1)}k`;
  return `${(n / 1e6).toFixed(2)}M`;
}

function bytesRate(b) {
  if (b < 1024) return `${b.toFixed(0)} B/s`;
  if (b < 1024 * 1024) return `${(b / 1024).toFixed(1)} KiB/s`;
  return `${(b / 1024 / 1024).toFixed(2)} MiB/s`;
}

function element(tag, className, text) {
  const e = document.createElement(tag);
  if (className) e.className = className;
  if (text !== undefined) e.textContent = text;
  return e;
}

// The panel is refreshed four times a second; writing a text or class it
// already shows would still make the browser lay out and repaint it, which
// with twenty idle tabs under a software renderer cost most of a core.
function setText(element, text) {
  if (element.textContent !== text) element.textContent = text;
}
function setClass(element, name) {
  if (element.className !== name) element.className = name;
}

export class Hud {
  // handlers: {onPreset(name), onCodec(name), onWireframe(on), onRegionColours(on),
  // onCage(on), onLevel(delta), onTolerance(px)}
  constructor(root, handlers) {
    this.root = root;
    this.h = handlers;
    root.classList.add('hud');
    root.innerHTML = `
      <div class="hud-title"><span class="hud-brand">Tessera</span><span data-f="glance"></span>
        <button class="hud-fold" title="fold (H)" aria-label="fold the panel">▾</button></div>
      <div class="hud-body">
        <div class="hud-row" data-f="doc"></div>
        <div class="hud-row"><span data-f="latency"></span><span data-f="rate"></span></div>
        <div class="hud-row" data-f="hash"></div>
        <div class="hud-row hud-controls">
          <label>LOD <select data-f="preset"></select></label>
          <label>codec <select data-f="codec" aria-label="region codec"><option value="draco">Draco</option><option value="meshopt">meshopt</option></select></label>
          <span class="hud-level">level <button data-f="down" aria-label="coarser edit level">−</button><b data-f="level"></b><button data-f="up" aria-label="finer edit level">+</button></span>
        </div>
        <div class="hud-row hud-controls" data-f="toleranceRow" hidden>
          <label>tolerance <input type="range" data-f="tolerance" min="-2" max="5" step="0.25" aria-label="screen-space error in pixels"></label>
          <span data-f="toleranceValue"></span>
        </div>
        <div class="hud-row hud-controls">
          <label><input type="checkbox" data-f="wire"> wire <kbd>W</kbd></label>
          <label><input type="checkbox" data-f="colours"> regions <kbd>R</kbd></label>
          <label><input type="checkbox" data-f="cageOn"> cage <kbd>O</kbd></label>
        </div>
        <div class="hud-row" data-f="cage" hidden></div>
        <div class="hud-row" data-f="pick"></div>
        <ul class="hud-people" data-f="people"></ul>
        <div class="hud-row hud-status" data-f="status"></div>
        <div class="hud-row hud-error" data-f="error"></div>
        <details class="hud-keys"><summary>keys</summary>
          drag a dot: move it · <kbd>Ctrl</kbd>+<kbd>Z</kbd>/<kbd>Y</kbd> undo/redo ·
          <kbd>C</kbd> crease the edge of the last two picks · <kbd>V</kbd> corner/smooth ·
          <kbd>[</kbd> <kbd>]</kbd> edit level · <kbd>P</kbd> dots · <kbd>O</kbd> cage · <kbd>F</kbd> fit · <kbd>Esc</kbd> unpick · <kbd>H</kbd> fold
        </details>
      </div>`;
    this.f = {};
    for (const e of root.querySelectorAll('[data-f]')) this.f[e.dataset.f] = e;
    for (const p of LOD_PRESETS) {
      const option = element('option', '', `${p.name} (${p.baseLevel}–${p.maxLevel}, ${p.angle}°)`);
      option.value = p.name;
      this.f.preset.append(option);
    }
    this.f.preset.addEventListener('change', () => this.h.onPreset(this.f.preset.value));
    this.f.codec.addEventListener('change', () => this.h.onCodec(this.f.codec.value));
    this.f.wire.addEventListener('change', () => this.h.onWireframe(this.f.wire.checked));
    this.f.colours.addEventListener('change', () => this.h.onRegionColours(this.f.colours.checked));
    this.f.cageOn.addEventListener('change', () => this.h.onCage(this.f.cageOn.checked));
    // A view's tolerance on a log scale, 0.25 to 32 pixels (the server
    // accepts 0.25 to 256; past 32 a phone's whole model is one tile).
    this.f.tolerance.addEventListener('input', () => this.h.onTolerance(2 ** Number(this.f.tolerance.value)));
    this.f.down.addEventListener('click', () => this.h.onLevel(-1));
    this.f.up.addEventListener('click', () => this.h.onLevel(1));
    root.querySelector('.hud-fold').addEventListener('click', () => this.toggle());
    // On a phone-sized page the open panel would cover the top third of the
    // frame, the model's top with it: it starts folded to its first line.
    if (window.matchMedia?.(SMALL_PAGE).matches) root.classList.add('folded');
  }

  // The page's rows the panel covers from the top, for fit-to-view to leave free.
  coveredTop() {
    return this.root.getBoundingClientRect().bottom;
  }

  toggle() {
    this.root.classList.toggle('folded');
  }

  // facts: {fps, triangles, regions, version, documentName, documentId,
  // role, latencyMs, bytesPerSecond, hash: {ours, server, matches} | null,
  // preset, codec ('draco' | 'meshopt'), wireframe, regionColours, cage (CageControl.facts()), level,
  // pick, points, pointsDrawn, people: [{sessionId, name, role, selection,
  // self}], views: {complete, frozen, tolerance, preview} | null, status,
  // error}
  update(facts) {
    const f = this.f;
    setText(f.glance, `v${facts.version}  ${shortCount(facts.triangles)} tris  ${facts.fps >= 0.5 ? `${facts.fps.toFixed(0)} fps` : 'idle'}`);
    // A view-dependent subscription counts tiles, says whether the surface's
    // preview is shown instead (counted apart), whether the camera's tiles
    // are all here, its tolerance, and whether the view is frozen (X).
    const views = facts.views;
    const regions = views
      ? `${views.preview ? `preview · ${facts.regions - 1}` : facts.regions} tiles${views.complete ? '' : ' (loading)'} · ` +
        `${views.tolerance} px${views.frozen ? ' · frozen' : ''}`
      : `${facts.regions} regions`;
    setText(f.doc, facts.documentId
      ? `doc ${facts.documentId}${facts.documentName ? ` “${facts.documentName}”` : ''} · ${regions} · ${ROLE_NAMES[facts.role] ?? 'role ' + facts.role}`
      : 'no document');
    setText(f.latency, facts.latencyMs === null ? 'edit→delta –' : `edit→delta ${facts.latencyMs.toFixed(1)} ms`);
    setText(f.rate, bytesRate(facts.bytesPerSecond));
    if (!facts.hash) {
      setText(f.hash, 'surface hash –');
      setClass(f.hash, 'hud-row');
    } else if (facts.hash.server === 0n) {
      setText(f.hash, `hash ${hex64(facts.hash.ours)} (server sent none)`);
      setClass(f.hash, 'hud-row');
    } else {
      setText(f.hash, `${facts.hash.matches ? '✓ hash matches' : '✗ hash differs'} ${hex64(facts.hash.ours).slice(0, 10)}…`);
      setClass(f.hash, `hud-row ${facts.hash.matches ? 'hud-good' : 'hud-bad'}`);
    }
    if (f.preset.value !== facts.preset && document.activeElement !== f.preset) f.preset.value = facts.preset;
    // A view-dependent subscription has a tolerance, not a preset.
    if (f.toleranceRow.hidden !== !facts.views) f.toleranceRow.hidden = !facts.views;
    if (f.preset.disabled !== Boolean(facts.views)) f.preset.disabled = Boolean(facts.views);
    // The server serves meshopt regions to LOD profiles only: a view's tiles
    // are Draco (docs/REGION_ENCODING.md "meshopt regions").
    if (f.codec.value !== facts.codec && document.activeElement !== f.codec) f.codec.value = facts.codec;
    if (f.codec.disabled !== Boolean(facts.views)) f.codec.disabled = Boolean(facts.views);
    if (facts.views) {
      const slider = String(Math.log2(facts.views.tolerance));
      if (f.tolerance.value !== slider && document.activeElement !== f.tolerance) f.tolerance.value = slider;
      setText(f.toleranceValue, `${facts.views.tolerance} px`);
    }
    if (f.wire.checked !== facts.wireframe) f.wire.checked = facts.wireframe;
    if (f.colours.checked !== facts.regionColours) f.colours.checked = facts.regionColours;
    this.cage(facts.cage);
    setText(f.level, String(facts.level));
    setText(f.pick, `${facts.pick} · ${shortCount(facts.points)} ${facts.pointsDrawn || facts.points === 0 ? 'dots' : 'vertices, no dots'}`);
    this.people(facts.people);
    setText(f.status, facts.status);
    setText(f.error, facts.error);
    if (f.error.hidden !== !facts.error) f.error.hidden = !facts.error;
  }

  // The cage's counts while it is on (docs/WEB_VIEWER.md "The control cage").
  cage(c) {
    const f = this.f;
    if (f.cageOn.checked !== c.on) f.cageOn.checked = c.on;
    if (f.cage.hidden !== !c.on) f.cage.hidden = !c.on;
    if (!c.on) return;
    const counts = `${shortCount(c.faces)} faces · ${shortCount(c.edges)} edges`;
    const what = {
      shown: `${counts} · ${shortCount(c.segments)} drawn`,
      'too large': `${counts}: too many to draw`,
      asking: 'asking the server…',
      refused: 'refused (below)',
      waiting: 'waiting for the document',
    }[c.status];
    setText(f.cage, `cage of level ${c.level}: ${what}`);
  }

  people(list) {
    const ul = this.f.people;
    const key = JSON.stringify(list.map((p) => [String(p.sessionId), p.name, p.role, p.selection.map(String)]));
    if (ul.dataset.key === key) return;
    ul.dataset.key = key;
    ul.replaceChildren(...list.map((p) => {
      const li = element('li');
      const swatch = element('span', 'hud-swatch');
      swatch.style.background = p.self ? '#ff4433' : `#${sessionColour(p.sessionId).getHexString()}`;
      const selection = p.selection.slice(0, 3).map((id) => idName(id)).join(' ') + (p.selection.length > 3 ? ' …' : '');
      li.append(swatch, element('span', '', `${p.name}${p.self ? ' (you)' : ''}`),
        element('span', 'hud-dim', ` ${ROLE_NAMES[p.role] ?? ''}${selection ? ' · ' + selection : ''}`));
      return li;
    }));
  }
}
