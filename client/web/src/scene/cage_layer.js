// The control cage on screen (docs/WEB_VIEWER.md "The control cage"): the
// cage's edges as line segments between the limit positions of the control
// points the page shows. A chord between two limit points lies inside a
// convex surface, so a depth test would hide most of it: the lines are drawn
// over the surface (no depth test, like a collaborator's picks), and an edge
// is left out unless one of its cage faces turns its front to the camera,
// which keeps the far side's edges off the near side. (Not the ends' limit
// normals: a vertex on a crease has one per side, and the page keeps one.)
// The dots (control_points.js) still draw over the lines. Rebuilt before every frame drawn, since what faces the
// camera changes as it moves; beyond MAX_EDGES no line is drawn (they would
// hide the surface), as the dots stop at 4,000.
import * as THREE from 'three';
import { cageSegments } from './control_cage.js';

// Magenta: far from the surface's grey, the dots' white, the hover ring's
// yellow and the page's blue-grey background.
export const CAGE_COLOUR = 0xff3fd0;
// About the edges of a quad mesh of the dots' 4,000 vertices.
export const MAX_EDGES = 8000;

export class CageLayer {
  // onChange: the view must draw again.
  constructor(scene, onChange) {
    this.onChange = onChange;
    this.cage = null; // cageEdges' result, or null: nothing drawn
    this.segments = 0; // segments in the last frame drawn
    this.buffer = new Float32Array(0);
    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.LineBasicMaterial({ color: CAGE_COLOUR, depthTest: false, depthWrite: false, toneMapped: false });
    this.lines = new THREE.LineSegments(this.geometry, this.material);
    this.lines.frustumCulled = false;
    // After the surface (0), before the dots (5, and transparent: drawn last).
    this.lines.renderOrder = 4;
    this.lines.visible = false;
    scene.add(this.lines);
  }

  // Whether the cage is too large to draw.
  get tooLarge() {
    return this.cage !== null && this.cage.edges.length > MAX_EDGES;
  }

  // The cage to draw (control_cage.js cageEdges), or null for none.
  setCage(cage) {
    if (cage === this.cage) return;
    this.cage = cage;
    const edges = cage && !this.tooLarge ? cage.edges.length : 0;
    this.buffer = new Float32Array(6 * edges);
    this.geometry.setAttribute('position', new THREE.BufferAttribute(this.buffer, 3));
    this.geometry.setDrawRange(0, 0);
    this.segments = 0;
    this.lines.visible = edges > 0;
    this.onChange();
  }

  // Before a frame: the segments of the edges whose ends lookup(id) finds
  // ({position}) and that a face towards `eye` has (the camera's world
  // position, [x, y, z]; control_cage.js cageSegments).
  update(lookup, eye) {
    if (!this.lines.visible) return;
    const { segments } = cageSegments(this.cage, lookup, eye, this.buffer);
    this.segments = segments;
    this.geometry.setDrawRange(0, 2 * segments);
    this.geometry.getAttribute('position').needsUpdate = true;
  }
}
